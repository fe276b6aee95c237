#!/usr/bin/env bash
# The environment's cost per pass (issue 20, docs/design.md §5.9): `vct render` of the same scenes by a build
# without the environment (the constant ambient of before: VCT_BEFORE, e.g. a build of main before issue 20)
# and by this build, alternated A B A B in one session, every pass run every frame (--recompute-every-frame),
# medians over the timed frames. Scenes: plane (sky), courtyard (sky; exported to .glb for the build without
# it) and cornell (constant, as before), and courtyard with --bounces 2 (the bounce pass sees the sky).
# Writes benchmarks/results/<device>-<size>-environment-ab.md.
# Usage: VCT_BEFORE=/path/to/old/vct benchmarks/environment_ab.sh   (ENV_SIZE [320x180], ENV_FRAMES [40],
#        ENV_WARMUP [10], ENV_REPEATS [2])
set -euo pipefail
source "$(dirname "$0")/common.sh"
after="${VCT:-build/vct}"
before="${VCT_BEFORE:?set VCT_BEFORE to a vct built without the environment}"
size="${ENV_SIZE:-320x180}" frames="${ENV_FRAMES:-40}" warmup="${ENV_WARMUP:-10}" repeats="${ENV_REPEATS:-2}"
work="$(mktemp -d)"
"$after" export-scene --scene courtyard --out "$work/courtyard.glb" >/dev/null
run() {  # run LABEL BINARY SCENE ARGS...
    local label="$1" bin="$2" scene="$3"
    shift 3
    "$bin" render --scene "$scene" --size "$size" --frames "$frames" --warmup "$warmup" --recompute-every-frame \
        --out "$work/$label" "$@" >"$work/$label.log"
}
device=""
table="| scene | flags | pass | without (ms) | with (ms) | ratio |\n| --- | --- | --- | --- | --- | --- |\n"
for spec in "plane|" "$work/courtyard.glb|" "cornell|" "$work/courtyard.glb|--bounces 2"; do
    scene="${spec%%|*}" flags="${spec#*|}"
    name="$(basename "${scene%.glb}")"
    for r in $(seq "$repeats"); do
        # shellcheck disable=SC2086
        run "$name-before-$r" "$before" "$scene" $flags
        # shellcheck disable=SC2086
        run "$name-after-$r" "$after" "$scene" $flags
    done
    device="$(sed -n 's/^device: //p' "$work/$name-after-1.log")"
    # Per pass: the median of the repeats' medians.
    for pass in $(awk '/^pass/{f=1;next} /^fps/{f=0} f{print $1}' "$work/$name-after-1.log"); do
        b="$(for r in $(seq "$repeats"); do awk -v p="$pass" '$1==p{print $2}' "$work/$name-before-$r.log"; done | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}')"
        a="$(for r in $(seq "$repeats"); do awk -v p="$pass" '$1==p{print $2}' "$work/$name-after-$r.log"; done | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}')"
        ratio="$(awk -v a="$a" -v b="$b" 'BEGIN{ if (b > 0) printf "%.2f", a / b; else print "-" }')"
        table+="| $name | ${flags:-} | $pass | $b | $a | $ratio |\n"
    done
done
slug="$(echo "$device" | tr -cs 'A-Za-z0-9' '-' | sed 's/-*$//')"
out="benchmarks/results/$slug-$size-environment-ab.md"
{
    echo "# The environment's cost per pass ($device, $size)"
    echo
    echo "\`benchmarks/environment_ab.sh\`: without = \`$before\` (constant ambient), with = \`$after\`; alternated"
    echo "$repeats times each in one session, --recompute-every-frame, $frames frames ($warmup warm-up), medians."
    echo
    printf "%b" "$table"
} >"$out"
echo "wrote $out"
