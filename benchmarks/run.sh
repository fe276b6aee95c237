#!/usr/bin/env bash
# Per-pass GPU timings of the default scene: medians over >= 30 frames after a warm-up, from timestamp queries.
# Writes benchmarks/results/<device>-<size>[-flags].json (the program's timings.json) and prints the table.
# Usage: benchmarks/run.sh [SIZE] [extra vct render flags...]   (build first: cmake --build build)
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-1280x720}"
shift || true
out="$(mktemp -d)"
build/vct render --scene cornell --size "$size" --frames 50 --warmup 10 --out "$out" "$@"
slug="$(device_slug "$out/timings.json")"
name="${slug}-${size}$(flags_suffix "$@")"
cp "$out/timings.json" "benchmarks/results/${name}.json"
echo "recorded benchmarks/results/${name}.json"
