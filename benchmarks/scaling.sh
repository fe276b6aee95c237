#!/usr/bin/env bash
# How each pass grows with the pixel count (160x90 … 1280x720) and the voxel resolution (32³ … 256³ at
# 320x180): `vct benchmark --mode scaling` (default configuration, cornell and hall, all points interleaved in blocks in
# one run), then benchmarks/plot_scaling.py draws the JSON and fits each pass's growth exponent.
# Writes benchmarks/results/<device>-scaling.{json,md} and <device>-scaling-{pixels,voxels}.png.
# Usage: benchmarks/scaling.sh [--quick] [extra vct benchmark flags...]   (build first; --quick: a few frames,
# for trying the script, not for claims)
set -euo pipefail
source "$(dirname "$0")/common.sh"
frames=40 warmup=8
if [ "${1:-}" = "--quick" ]; then frames=6 warmup=2; shift; fi
# SCALING_SCENES (default "cornell hall"): one run per scene; cornell's results keep their names, another
# scene's carry its name (<device>-scaling-hall.*).
for scene in ${SCALING_SCENES:-cornell hall}; do
    suffix=""
    [ "$scene" = cornell ] || suffix="-$scene"
    out="$(mktemp -d)"
    build/vct benchmark --mode scaling --scene "$scene" --size 320x180 --frames "$frames" --warmup "$warmup" \
        --out "$out" "$@"
    slug="$(device_slug "$out/scaling.json")"
    for ext in json md; do cp "$out/scaling.$ext" "benchmarks/results/${slug}-scaling${suffix}.$ext"; done
    if ! "$PYTHON" -c 'import matplotlib' 2>/dev/null; then
        echo "python3-matplotlib is needed for the plots: apt-get install -y python3-matplotlib" >&2
        exit 1
    fi
    "$PYTHON" benchmarks/plot_scaling.py "benchmarks/results/${slug}-scaling${suffix}.json" \
        "benchmarks/results/${slug}-scaling${suffix}"
done
