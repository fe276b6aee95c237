#!/usr/bin/env bash
# Speed against error as one report (issue 9): `vct benchmark --mode report` on the report scenes
# (scenes/report_scenes.json: cornell, plane, and DamagedHelmet when ../shared/scenes has it) with a static, a
# moving (the scene's camera path) and a cut camera, then `--mode study` (the parameter study of Tokuyoshi
# 2015, Fig. 6), then the plots made from the JSON (benchmarks/plot_report.py).
# The truth as a second reference (unless REPORT_TRUTH=0): the report also writes the static camera's last frame
# of every configuration, the every-pixel trace's included (--dump-last); `vct reference` path-traces that frame
# once per scene (the scene camera, --frame FRAMES-1, at SIZE) and `vct compare --reference-dir` measures each
# configuration against it (docs/truth_compare.md). The metrics go to ...-report-truth-SCENE.json, and the
# Pareto plots and ...-report-truth.md show them beside the error against the every-pixel trace.
# Writes benchmarks/results/<device>-<size>-report.{json,md}, ...-study.{json,md}, ...-report-*.png and
# ...-report-truth-SCENE.json, ...-report-truth.md.
# Usage: benchmarks/report.sh [SIZE] [extra vct benchmark flags...]
#        (build first; ~15 min on lavapipe, 2 cores, plus the references: ~15 s per scene at 320x180, 256 spp)
# Environment (defaults in brackets):
#   REPORT_TRUTH [1]          0: no dump, no reference, no truth columns
#   REPORT_TRUTH_SPP [256]    samples per pixel of each reference
#   REPORT_TRUTH_SEED, REPORT_TRUTH_THREADS   passed on to vct reference
#   REPORT_WORK               where the report, the dump, the references and the compare JSONs go (default: a
#                             fresh temporary directory); references there with the same settings are reused
#   VCT [build/vct]           the program
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-320x180}"
shift || true
vct="${VCT:-build/vct}"
truth="${REPORT_TRUTH:-1}"
case "$truth" in 0 | 1) ;; *) echo "report.sh: REPORT_TRUTH: expected 0 or 1, not '$truth'" >&2; exit 2 ;; esac
spp="${REPORT_TRUTH_SPP:-256}"
[ -x "$vct" ] || { echo "report.sh: $vct not found: build first (cmake --build build)" >&2; exit 1; }
out="${REPORT_WORK:-$(mktemp -d)}"
mkdir -p "$out"
dump="$out/last"
dump_flags=()
if [ "$truth" = 1 ]; then
    rm -rf "$dump"  # no configuration of an earlier run left behind
    dump_flags=(--dump-last "$dump")
fi
# One bounce: the errors are against the every-pixel trace of a light that stands still (the default's gathers
# converge over the first rounds and the history lags them, docs/design.md §5.7). A later --bounces wins.
"$vct" benchmark --mode report --size "$size" --frames 64 --warmup 10 --block 8 --bounces 1 --out "$out" \
    "${dump_flags[@]}" "$@"
"$vct" benchmark --mode study --size "$size" --bounces 1 --out "$out" "$@"
slug="$(device_slug "$out/report.json")"
prefix="benchmarks/results/${slug}-${size}"
for name in report study; do
    for ext in json md; do cp "$out/$name.$ext" "${prefix}-$name.$ext"; done
done

truth_files=()
if [ "$truth" = 1 ]; then
    manifest="$dump/manifest.json"
    reference_flags=()
    [ -n "${REPORT_TRUTH_SEED:-}" ] && reference_flags+=(--seed "$REPORT_TRUTH_SEED")
    [ -n "${REPORT_TRUTH_THREADS:-}" ] && reference_flags+=(--threads "$REPORT_TRUTH_THREADS")
    # One line per dumped scene: its directory, name, scene (built-in name or absolute glTF path), the frame,
    # WxH and the exposure of the report.
    scene_lines="$("$PYTHON" - "$manifest" <<'EOF'
import json
import sys

m = json.load(open(sys.argv[1]))
for s in m["scenes"]:
    print("\t".join([s["dir"], s["name"], s["scene"], str(m["frame"]), f"{m['width']}x{m['height']}",
                     repr(float(m["exposure"]))]))
EOF
)"
    [ -n "$scene_lines" ] || echo "note: no static camera in the report (--cameras): no truth"
    while IFS=$'\t' read -r -u 3 dir name scene frame wxh exposure; do
        [ -n "$dir" ] || continue
        reference="$out/truth/reference-$dir"
        json_dir="$out/truth/json/$dir"
        mkdir -p "$json_dir"
        # vct reference of the static camera's last frame (the scene camera: no --camera-path), reused from
        # REPORT_WORK when it was rendered with the same settings.
        cached_reference "$reference" --scene "$scene" --size "$wxh" --frame "$frame" --spp "$spp" \
            --bounces 1 --exposure "$exposure" "${reference_flags[@]}"
        configs="$("$PYTHON" -c 'import json, sys
for s in json.load(open(sys.argv[1]))["scenes"]:
    if s["dir"] == sys.argv[2]:
        print("\n".join(c["dir"] for c in s["configs"]))' "$manifest" "$dir")"
        echo "== vct compare --reference-dir $reference: $(echo "$configs" | wc -l) configurations of $name"
        for config in $configs; do
            # The per-surface table goes to a log beside the JSON.
            "$vct" compare --reference-dir "$reference" --image-dir "$dump/$dir/$config" \
                --json "$json_dir/$config.json" >"$json_dir/$config.txt"
        done
        # truth-SCENE.json: configuration name → its compare metrics, with the reference's settings.
        "$PYTHON" - "$manifest" "$dir" "$json_dir" "$reference" "$spp" "${prefix}-report-truth-$dir.json" <<'EOF'
import json
import os
import sys

manifest_path, scene_dir, json_dir, reference_dir, spp, out_path = sys.argv[1:]
manifest = json.load(open(manifest_path))
scene = next(s for s in manifest["scenes"] if s["dir"] == scene_dir)
seconds_path = reference_dir + ".seconds"
truth = {
    "scene": scene["name"],
    "scene_path": scene["scene"],
    "camera": manifest["camera"],
    "camera_path": scene["camera_path"],
    "frame": manifest["frame"],
    "width": manifest["width"],
    "height": manifest["height"],
    "exposure": manifest["exposure"],
    "spp": int(spp),
    "reference_seconds": int(open(seconds_path).read()) if os.path.exists(seconds_path) else None,
    "order": [c["name"] for c in scene["configs"]],
    "configs": {},
}
for c in scene["configs"]:
    compare = json.load(open(os.path.join(json_dir, c["dir"] + ".json")))
    truth.setdefault("reference", compare.get("reference"))
    entry = {"dir": c["dir"], "trace_scale": c["trace_scale"], "frame_median_ms": c["frame_median_ms"]}
    for key in ("errors", "image", "surfaces", "pixels", "background_pixels"):
        if key in compare:
            entry[key] = compare[key]
    truth["configs"][c["name"]] = entry
with open(out_path, "w") as f:
    json.dump(truth, f, indent=2)
    f.write("\n")
print(f"wrote {out_path}")
EOF
        truth_files+=("${prefix}-report-truth-$dir.json")
    done 3<<<"$scene_lines"
fi

"$PYTHON" benchmarks/plot_report.py "${prefix}-report.json" "${prefix}-study.json" "${prefix}-report" \
    "${truth_files[@]}"
echo "recorded ${prefix}-{report,study}.{json,md} and ${prefix}-report-*.png${truth_files:+, ${prefix}-report-truth*}"
echo "work files (dump, references, compare JSONs) in $out"
