#!/usr/bin/env bash
# vct against ground truth (docs/truth_compare.md). For each scene: path-traced references by `vct reference`
# (one bounce; all bounces; one bounce with diffuse-only secondary vertices), rendered once at the frame vct
# writes (its last); then vct at 32³/64³/128³ voxels × trace scale 1 and 4 after F frames (`vct render --aux`),
# each measured with `vct compare --reference-dir` against every reference (ratios per surface, tone-mapped PSNR,
# relMSE without the reference's noise, log2 ratio maps); against the diffuse-secondary one, the same render with
# --voxel-glossy off. benchmarks/plot_truth.py then writes truth.md,
# truth_ratios.png and truth_error_vs_voxels.png and copies the ratio maps.
# Writes benchmarks/results/<device>-truth/ (TRUTH_QUICK=1: <device>-truth-quick/; the directory is replaced).
# Usage: benchmarks/truth.sh [SCENE...]   (build first; default scenes: cornell plane courtyard cornell-turned, and
#        ../shared/scenes/{DamagedHelmet,BoxVertexColors}/glTF/*.gltf when present)
# Environment (defaults in brackets):
#   TRUTH_SIZE [320x180]  TRUTH_SPP [256]  TRUTH_FRAMES [64]  TRUTH_VOXELS ["32 64 128"]  TRUTH_SCALES ["1 4"]
#   TRUTH_REFERENCES ["1 all diffuse"]  which references: one bounce, all bounces, --secondary diffuse
#   TRUTH_SEED, TRUTH_THREADS, TRUTH_EXPOSURE   passed on to vct reference (and the exposure to render, compare)
#   TRUTH_WORK   where renders go (default: a fresh temporary directory); references already there with the same
#                settings are reused, so a run can be resumed
#   TRUTH_QUICK=1   64x36, 8 spp, 8 frames: a smoke test of the script, not for claims
#   TRUTH_NOISE_SEED  when set, a second reference of each kind with this seed (another than TRUTH_SEED's, default
#                1), passed to compare as --second-reference-dir: the reference's own noise in the sRGB PSNRs
#   TRUTH_TAG    appended to the results directory's name (e.g. t0 for TRUTH_FRAMES=1: the static pose at t = 0)
#   TRUTH_RENDER_FLAGS  extra `vct render` flags for every vct image (e.g. "--cone-jitter on"; split on spaces),
#                after --bounces 1 unless they name --bounces themselves
#   VCT          the program [build/vct]
set -euo pipefail
# Scene arguments that are files are made absolute before common.sh changes to the repository root.
scenes=()
for arg in "$@"; do
    if [ -e "$arg" ]; then scenes+=("$(realpath "$arg")"); else scenes+=("$arg"); fi
done
source "$(dirname "$0")/common.sh"

vct="${VCT:-build/vct}"
if [ "${TRUTH_QUICK:-0}" = 1 ]; then
    size="${TRUTH_SIZE:-64x36}" spp="${TRUTH_SPP:-8}" frames="${TRUTH_FRAMES:-8}" suffix="-quick"
else
    size="${TRUTH_SIZE:-320x180}" spp="${TRUTH_SPP:-256}" frames="${TRUTH_FRAMES:-64}" suffix=""
fi
voxels="${TRUTH_VOXELS:-32 64 128}"
scales="${TRUTH_SCALES:-1 4}"
references="${TRUTH_REFERENCES:-1 all diffuse}"
for kind in $references; do
    case "$kind" in 1 | all | diffuse) ;; *) echo "truth.sh: TRUTH_REFERENCES: unknown '$kind' (1, all, diffuse)" >&2; exit 2 ;; esac
done
frame=$((frames - 1))  # vct render writes its last frame, at t = (frames - 1) / 60 s
work="${TRUTH_WORK:-$(mktemp -d)}"
mkdir -p "$work/json" "$work/maps"
[ -x "$vct" ] || { echo "truth.sh: $vct not found: build first (cmake --build build)" >&2; exit 1; }

if [ "${#scenes[@]}" -eq 0 ]; then
    # courtyard: the open scene, lit mostly by the sun and the procedural sky (docs/design.md §5.9); cornell-turned:
    # a closed room off the grid's axes (§5.6).
    scenes=(cornell plane courtyard cornell-turned)
    # From ../shared/scenes when present: a textured model, and a lone cube under the sky, whose faces lie in the
    # grid's edge layer (docs/design.md §5.3: a cone leaving them outwards once read its own face there).
    for model in DamagedHelmet BoxVertexColors; do
        file="$(realpath -m "../shared/scenes/$model/glTF/$model.gltf")"
        if [ -f "$file" ]; then
            scenes+=("$file")
        else
            echo "note: $file not found: $model skipped"
        fi
    done
fi

exposure_flags=()
[ -n "${TRUTH_EXPOSURE:-}" ] && exposure_flags=(--exposure "$TRUTH_EXPOSURE")
# shellcheck disable=SC2206  # split on purpose: several flags in one variable
# vct renders one bounce unless TRUTH_RENDER_FLAGS names --bounces: most references are one-bounce, and the report
# measures the cone tracer itself (TRUTH_RENDER_FLAGS="--bounces all" TRUTH_REFERENCES=all for the default,
# docs/design.md §5.7). Extra flags used to replace the --bounces 1, and "--cone-jitter on" alone then rendered
# every bounce against the one-bounce truth (round 15, caught by a wall at 2.5×).
render_flags=(${TRUTH_RENDER_FLAGS:-})
[[ " ${render_flags[*]} " == *" --bounces "* ]] || render_flags=(--bounces 1 "${render_flags[@]}")
reference_flags=("${exposure_flags[@]}")
[ -n "${TRUTH_SEED:-}" ] && reference_flags+=(--seed "$TRUTH_SEED")
[ -n "${TRUTH_THREADS:-}" ] && reference_flags+=(--threads "$TRUTH_THREADS")
# The second references: the same flags with the other seed.
noise_reference_flags=("${exposure_flags[@]}" --seed "${TRUTH_NOISE_SEED:-}")
[ -n "${TRUTH_THREADS:-}" ] && noise_reference_flags+=(--threads "$TRUTH_THREADS")

# scene_name SCENE: a built-in name as it is, a file by its base name ("DamagedHelmet").
scene_name() { basename "${1%.*}"; }

# reference_dir NAME KIND: where that reference goes (R/reference-S, reference-S-all, reference-S-diffuse).
reference_dir() {
    case "$2" in
        1) echo "$work/reference-$1" ;;
        all) echo "$work/reference-$1-all" ;;
        diffuse) echo "$work/reference-$1-diffuse" ;;
    esac
}

reference_label() {
    case "$1" in 1) echo one-bounce ;; all) echo all-bounces ;; diffuse) echo one-bounce-diffuse-secondary ;; esac
}

# render_reference SCENE NAME KIND: vct reference, unless TRUTH_WORK already holds it with the same settings; with
# TRUTH_NOISE_SEED the second one too (same settings, that seed) into DIR-noise.
render_reference() {
    local flags=(--bounces 1)
    case "$3" in all) flags=(--bounces all) ;; diffuse) flags=(--bounces 1 --secondary diffuse) ;; esac
    cached_reference "$(reference_dir "$2" "$3")" --scene "$1" --size "$size" --spp "$spp" --frame "$frame" \
        "${flags[@]}" "${reference_flags[@]}"
    if [ -n "${TRUTH_NOISE_SEED:-}" ]; then
        cached_reference "$(reference_dir "$2" "$3")-noise" --scene "$1" --size "$size" --spp "$spp" \
            --frame "$frame" "${flags[@]}" "${noise_reference_flags[@]}"
    fi
}

# annotate JSON KEY=VALUE...: records the configuration (and vct's timings) in a compare JSON as "config".
annotate() {
    "$PYTHON" - "$@" <<'EOF'
import json
import os
import sys

path = sys.argv[1]
with open(path) as f:
    data = json.load(f)
config = {}
for item in sys.argv[2:]:
    key, value = item.split("=", 1)
    try:
        config[key] = json.loads(value)
    except ValueError:
        config[key] = value
timings = os.path.join(data["image_dir"], "timings.json")
if os.path.exists(timings):
    with open(timings) as f:
        t = json.load(f)
    config["device"] = t.get("device")
    config["frame_median_ms"] = t.get("frame_median_ms")
    config["settings"] = t.get("settings")
data["config"] = config
with open(path, "w") as f:
    json.dump(data, f, indent=2, sort_keys=True)
    f.write("\n")
EOF
}

render_help="$("$vct" render --help)"
slug=""
produced=()
for scene in "${scenes[@]}"; do
    name="$(scene_name "$scene")"
    for kind in $references; do render_reference "$scene" "$name" "$kind"; done
    for v in $voxels; do
        for t in $scales; do
            image="$work/vct-$name-v$v-s$t"
            echo "== vct render --scene $scene --voxels $v --trace-scale $t ${render_flags[*]} ($size, $frames frames) -> $image"
            "$vct" render --scene "$scene" --size "$size" --frames "$frames" --voxels "$v" --trace-scale "$t" \
                "${exposure_flags[@]}" "${render_flags[@]}" --aux --out "$image"
            [ -n "$slug" ] || slug="$(device_slug "$image/timings.json")"
            # Against the reference without glossy-to-diffuse transport: vct's voxels without it too (Lambertian,
            # docs/design.md §5.11), so that the cone tracer's error shows apart from the transport's.
            # (A build from before --voxel-glossy, measured for a before/after table, has only Lambertian voxels.)
            lambertian="$image-lambertian"
            if [[ "$render_help" != *--voxel-glossy* ]]; then
                lambertian="$image"
            elif [[ " $references " == *" diffuse "* ]]; then
                echo "== the same with --voxel-glossy off -> $lambertian"
                "$vct" render --scene "$scene" --size "$size" --frames "$frames" --voxels "$v" --trace-scale "$t" \
                    --voxel-glossy off "${exposure_flags[@]}" "${render_flags[@]}" --aux --out "$lambertian"
            fi
            for kind in $references; do
                stem="truth-$name-v$v-s$t-vs-$kind"
                json="$work/json/$stem.json"
                measured="$image"
                [ "$kind" = diffuse ] && measured="$lambertian"
                noise_flags=()
                [ -n "${TRUTH_NOISE_SEED:-}" ] &&
                    noise_flags=(--second-reference-dir "$(reference_dir "$name" "$kind")-noise")
                "$vct" compare --reference-dir "$(reference_dir "$name" "$kind")" --image-dir "$measured" \
                    --json "$json" --maps "$work/maps/$stem" "${exposure_flags[@]}" "${noise_flags[@]}"
                produced+=("$json")
                seconds_file="$(reference_dir "$name" "$kind").seconds"
                reference_seconds=null
                [ -f "$seconds_file" ] && reference_seconds="$(cat "$seconds_file")"
                annotate "$json" "scene=$name" "scene_path=$scene" "voxels=$v" "trace_scale=$t" \
                    "reference_kind=$kind" "reference_label=$(reference_label "$kind")" "size=$size" \
                    "spp=$spp" "frames=$frames" "frame=$frame" \
                    "reference_seconds=$reference_seconds" "render_flags=${render_flags[*]}"
            done
        done
    done
done

results="benchmarks/results/${slug}-truth${suffix}${TRUTH_TAG:+-$TRUTH_TAG}"
rm -rf "$results"
mkdir -p "$results"
cp "${produced[@]}" "$results/"
"$PYTHON" benchmarks/plot_truth.py "$results" "$results"/truth-*.json
echo "recorded $results/ (truth.md, truth-*.json, truth_*.png, maps/); renders in $work"
