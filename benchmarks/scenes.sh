#!/usr/bin/env bash
# The default configuration on every scene (built-in rooms and the glTF models in ../shared/scenes, skipped when
# absent), frames interleaved in blocks in one run: `vct benchmark --mode scenes`.
# Writes benchmarks/results/<device>-<size>-scenes[-flags].{json,md} and prints the table.
# Usage: benchmarks/scenes.sh [SIZE] [extra vct benchmark flags, e.g. --recompute-every-frame]   (build first)
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-320x180}"
shift || true
out="$(mktemp -d)"
build/vct benchmark --mode scenes --size "$size" --frames 48 --warmup 8 --out "$out" "$@"
slug="$(device_slug "$out/scenes.json")"
name="${slug}-${size}-scenes$(flags_suffix "$@")"
for ext in json md; do cp "$out/scenes.$ext" "benchmarks/results/${name}.$ext"; done
echo "recorded benchmarks/results/${name}.{json,md}"
