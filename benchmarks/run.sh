#!/usr/bin/env bash
# Per-pass GPU timings of the default scene: medians over >= 30 frames after a warm-up, from timestamp queries.
# Writes benchmarks/results/<device>-<size>.json (the program's timings.json) and prints the table.
# Usage: benchmarks/run.sh [SIZE] [extra vct render flags...]   (build first: cmake --build build)
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-1280x720}"
shift || true
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
out="$(mktemp -d)"
build/vct render --scene cornell --size "$size" --frames 50 --warmup 10 --out "$out" "$@"
device="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"])' "$out/timings.json")"
slug="$(echo "$device" | tr -cs 'A-Za-z0-9' '-' | sed 's/-*$//')"
# Extra flags become part of the name, so configurations measured side by side do not overwrite each other.
flags="$(echo "$*" | tr -cs 'A-Za-z0-9' '-' | sed 's/^-*//; s/-*$//')"
[ -n "$flags" ] && size="${size}-${flags}"
mkdir -p benchmarks/results
cp "$out/timings.json" "benchmarks/results/${slug}-${size}.json"
echo "recorded benchmarks/results/${slug}-${size}.json"
