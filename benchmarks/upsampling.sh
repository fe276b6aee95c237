#!/usr/bin/env bash
# Speed against error of the upsampling (docs/design.md §8), one run: `vct benchmark` renders the reference
# (trace scale 1) and the bilinear / normal / sg configurations (with and without adaptive re-tracing)
# interleaved in blocks of frames on one device, and compares their last frames with the reference's.
# Writes benchmarks/results/<device>-<size>-s<scale>-upsampling[-flags].{json,md} and prints the table.
# Usage: benchmarks/upsampling.sh [SIZE] [TRACE_SCALE] [extra vct benchmark flags...]   (build first)
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-640x360}"
scale="${2:-4}"
shift 2 || shift $# || true
out="$(mktemp -d)"
# One bounce: the upsampling's error is measured against the every-pixel trace of a light that stands still; the
# default's gathers (--bounces all) converge over the first rounds, and the history lags the rising light
# (docs/design.md §5.7). A later --bounces in the extra flags wins.
build/vct benchmark --scene cornell --size "$size" --frames 64 --warmup 10 --trace-scale "$scale" --bounces 1 \
    --out "$out" "$@"
slug="$(device_slug "$out/benchmark.json")"
# Extra flags name the files too (as run.sh's and scenes.sh's), so that a configuration measured beside the default
# (`--trace-layout pixel`, say) does not overwrite the default's results.
name="${slug}-${size}-s${scale}-upsampling$(flags_suffix "$@")"
for ext in json md; do cp "$out/benchmark.$ext" "benchmarks/results/${name}.$ext"; done
echo "recorded benchmarks/results/${name}.{json,md}"
