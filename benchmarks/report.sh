#!/usr/bin/env bash
# Speed against error as one report (issue 9): `vct benchmark --mode report` on the report scenes
# (scenes/report_scenes.json: cornell, plane, and DamagedHelmet when ../shared/scenes has it) with a static, a
# moving (the scene's camera path) and a cut camera, then `--mode study` (the parameter study of Tokuyoshi
# 2015, Fig. 6), then the plots made from the JSON (benchmarks/plot_report.py).
# Writes benchmarks/results/<device>-<size>-report.{json,md}, ...-study.{json,md} and ...-report-*.png.
# Usage: benchmarks/report.sh [SIZE] [extra vct benchmark flags...]   (build first; ~15 min on lavapipe, 2 cores)
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-320x180}"
shift || true
out="$(mktemp -d)"
build/vct benchmark --mode report --size "$size" --frames 64 --warmup 10 --block 8 --out "$out" "$@"
build/vct benchmark --mode study --size "$size" --out "$out" "$@"
slug="$(device_slug "$out/report.json")"
prefix="benchmarks/results/${slug}-${size}"
for name in report study; do
    for ext in json md; do cp "$out/$name.$ext" "${prefix}-$name.$ext"; done
done
"$PYTHON" benchmarks/plot_report.py "${prefix}-report.json" "${prefix}-study.json" "${prefix}-report"
echo "recorded ${prefix}-{report,study}.{json,md} and ${prefix}-report-*.png"
