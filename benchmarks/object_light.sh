#!/usr/bin/env bash
# How the light one object sends to the others compares with the truth, apart from everything else (docs/design.md
# §5.6). From one scene (a built-in, exported by `vct export-scene`) benchmarks/edit_glb.py makes two variants:
#   absorb  the object reflects nothing (it still occludes): everything's light but the object's;
#   glow    no lights, the object glows with radiance 1 to every side: only the cones' geometry is tested (how much
#           of a uniform emitter each surface gathers), not the voxels' lighting or lobes.
# Each of the three scenes gets a one-bounce path-traced reference (`vct reference`, at the frame vct writes) and a
# vct render per grid size (`render --aux`, trace scale 4, one bounce), measured by `vct compare --reference-dir`.
# benchmarks/object_light.py then writes a table per surface: vct ÷ truth for the whole scene, for the absorbing
# variant, for the object's own light (whole minus absorbing, in both), and for the glowing object.
# Usage: benchmarks/object_light.sh   (build first)
# Environment (defaults in brackets):
#   OBJECT_SCENE [cornell]  OBJECT_MATERIAL [gold]  OBJECT_VOXELS ["32 64 128"]  OBJECT_SIZE [320x180]
#   OBJECT_SPP [1024]  OBJECT_FRAMES [64]  OBJECT_TAG (appended to the results file's name)
#   OBJECT_WORK  where scenes, references and renders go (default: a fresh temporary directory); references already
#                there with the same settings are reused
#   VCT          the program [build/vct]
# Writes benchmarks/results/<device>-object-light-<scene>-<material><tag>.md.
set -euo pipefail
source "$(dirname "$0")/common.sh"

vct="${VCT:-build/vct}"
scene="${OBJECT_SCENE:-cornell}"
material="${OBJECT_MATERIAL:-gold}"
voxels="${OBJECT_VOXELS:-32 64 128}"
size="${OBJECT_SIZE:-320x180}"
spp="${OBJECT_SPP:-1024}"
frames="${OBJECT_FRAMES:-64}"
work="${OBJECT_WORK:-$(mktemp -d)}"
mkdir -p "$work"
frame=$((frames - 1))  # the frame vct render writes

"$vct" export-scene --scene "$scene" --out "$work/whole.glb" >/dev/null
"$PYTHON" benchmarks/edit_glb.py absorb "$work/whole.glb" "$work/absorb.glb" "$material"
"$PYTHON" benchmarks/edit_glb.py glow "$work/whole.glb" "$work/glow.glb" "$material"

slug=""
for variant in whole absorb glow; do
    cached_reference "$work/reference-$variant" --scene "$work/$variant.glb" --size "$size" --spp "$spp" \
        --frame "$frame" --bounces 1
    for n in $voxels; do
        out="$work/vct-$variant-$n"
        echo "== vct render $variant ${n}³"
        "$vct" render --scene "$work/$variant.glb" --size "$size" --frames "$frames" --voxels "$n" \
            --trace-scale 4 --bounces 1 --aux --out "$out" >/dev/null
        "$vct" compare --reference-dir "$work/reference-$variant" --image-dir "$out" \
            --json "$work/truth-$variant-$n.json" >/dev/null
        [ -n "$slug" ] || slug="$(device_slug "$out/timings.json")"
    done
done

result="benchmarks/results/$slug-object-light-$scene-$material${OBJECT_TAG:+-$OBJECT_TAG}.md"
"$PYTHON" benchmarks/object_light.py "$work" "$scene" "$material" "$size" "$spp" "$frames" $voxels >"$result"
echo "wrote $result"
