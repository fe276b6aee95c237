#!/usr/bin/env bash
# The cost of vertex colours (issue 20, docs/design.md §3.1): the Vertex grew from 48 to 64 bytes (COLOR_0), and
# gbuffer and voxelize read it. `vct render` of cornell by a build before the change (VCT_BEFORE, e.g. main's)
# and by this build, alternated A B A B in one session, every pass run every frame (--recompute-every-frame),
# medians over the timed frames; then BoxVertexColors (a mesh with COLOR_0, which the build before ignores)
# when ../shared/scenes has it. Writes benchmarks/results/<device>-<size>-vertex-colors.md.
# Usage: VCT_BEFORE=/path/to/old/vct benchmarks/vertex_color_ab.sh   (VC_SIZE [640x360], VC_FRAMES [40],
#        VC_WARMUP [10], VC_REPEATS [3])
set -euo pipefail
source "$(dirname "$0")/common.sh"
after="${VCT:-build/vct}"
before="${VCT_BEFORE:?set VCT_BEFORE to a vct built before vertex colours}"
size="${VC_SIZE:-640x360}" frames="${VC_FRAMES:-40}" warmup="${VC_WARMUP:-10}" repeats="${VC_REPEATS:-3}"
work="$(mktemp -d)"
run() {  # run LABEL BINARY SCENE
    "$2" render --scene "$3" --size "$size" --frames "$frames" --warmup "$warmup" --recompute-every-frame \
        --out "$work/$1" >"$work/$1.log"
}
scenes=(cornell)
box="../shared/scenes/BoxVertexColors/glTF/BoxVertexColors.gltf"  # from the repository root (common.sh)
[[ -f "$box" ]] && scenes+=("$box")
device=""
table="| scene | pass | before (ms) | after (ms) | ratio |\n| --- | --- | --- | --- | --- |\n"
median() { sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }
for scene in "${scenes[@]}"; do
    name="$(basename "${scene%.gltf}")"
    for r in $(seq "$repeats"); do
        run "$name-before-$r" "$before" "$scene"
        run "$name-after-$r" "$after" "$scene"
    done
    device="$(sed -n 's/^device: //p' "$work/$name-after-1.log")"
    # Per pass: the median of the repeats' medians (and every repeat's, for the spread).
    for pass in $(awk '/^pass/{f=1;next} /^fps/{f=0} f{print $1}' "$work/$name-after-1.log"); do
        all_b="$(for r in $(seq "$repeats"); do awk -v p="$pass" '$1==p{print $2}' "$work/$name-before-$r.log"; done)"
        all_a="$(for r in $(seq "$repeats"); do awk -v p="$pass" '$1==p{print $2}' "$work/$name-after-$r.log"; done)"
        b="$(echo "$all_b" | median)" a="$(echo "$all_a" | median)"
        ratio="$(awk -v a="$a" -v b="$b" 'BEGIN{ if (b > 0) printf "%.2f", a / b; else print "-" }')"
        table+="| $name | $pass | $b ($(echo $all_b | tr ' ' '/')) | $a ($(echo $all_a | tr ' ' '/')) | $ratio |\n"
    done
done
slug="$(echo "$device" | tr -cs 'A-Za-z0-9' '-' | sed 's/-*$//')"
out="benchmarks/results/$slug-$size-vertex-colors.md"
{
    echo "# Vertex colours: cost per pass ($device, $size)"
    echo
    echo "\`benchmarks/vertex_color_ab.sh\`: before = \`$before\` (48-byte vertex, no COLOR_0), after = \`$after\`"
    echo "(64-byte vertex); alternated $repeats times each in one session, --recompute-every-frame, $frames frames"
    echo "($warmup warm-up); per pass the median of the runs' medians, each run's in brackets."
    echo
    printf "%b" "$table"
} >"$out"
echo "wrote $out"
