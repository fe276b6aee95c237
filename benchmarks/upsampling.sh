#!/usr/bin/env bash
# Speed against error of the upsampling (DESIGN §5), one run: `vct benchmark` renders the reference (trace scale
# 1) and the bilinear / normal / sg configurations (with and without adaptive re-tracing) interleaved, frame by
# frame, on one device, and compares their last frames with the reference's.
# Writes benchmarks/results/<device>-<size>-s<scale>-upsampling.{json,md} and prints the table.
# Usage: benchmarks/upsampling.sh [SIZE] [TRACE_SCALE] [extra vct benchmark flags...]   (build first)
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-320x180}"
scale="${2:-4}"
shift 2 || shift $# || true
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
out="$(mktemp -d)"
build/vct benchmark --scene cornell --size "$size" --frames 64 --warmup 10 --trace-scale "$scale" --out "$out" "$@"
device="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"])' "$out/benchmark.json")"
slug="$(echo "$device" | tr -cs 'A-Za-z0-9' '-' | sed 's/-*$//')"
mkdir -p benchmarks/results
for ext in json md; do cp "$out/benchmark.$ext" "benchmarks/results/${slug}-${size}-s${scale}-upsampling.$ext"; done
echo "recorded benchmarks/results/${slug}-${size}-s${scale}-upsampling.{json,md}"
