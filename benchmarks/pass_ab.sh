#!/usr/bin/env bash
# Per-pass A/B of two builds: `vct render` by a build before a change (VCT_BEFORE) and by this one (VCT, default
# build/vct), alternated before/after REPEATS times in one session on each scene, medians over the timed frames of
# each run, then the median of the runs per pass. Writes benchmarks/results/<device>-<size>-<LABEL>-ab.md.
# Usage: VCT_BEFORE=/path/to/old/vct benchmarks/pass_ab.sh LABEL SCENE... [-- RENDER_ARGS...]
#        (AB_SIZE [640x360], AB_FRAMES [40], AB_WARMUP [10], AB_REPEATS [3])
set -euo pipefail
source "$(dirname "$0")/common.sh"
label="${1:?usage: pass_ab.sh LABEL SCENE... [-- RENDER_ARGS...]}"
shift
scenes=()
while [[ $# -gt 0 && "$1" != "--" ]]; do
    scenes+=("$1")
    shift
done
[[ $# -gt 0 ]] && shift
extra=("$@")
after="${VCT:-build/vct}"
before="${VCT_BEFORE:?set VCT_BEFORE to the vct built before the change}"
size="${AB_SIZE:-640x360}" frames="${AB_FRAMES:-40}" warmup="${AB_WARMUP:-10}" repeats="${AB_REPEATS:-3}"
work="$(mktemp -d)"
for scene in "${scenes[@]}"; do
    name="$(basename "${scene%.*}")"
    for r in $(seq "$repeats"); do
        for side in before after; do
            bin="$after"
            [[ "$side" == before ]] && bin="$before"
            "$bin" render --scene "$scene" --size "$size" --frames "$frames" --warmup "$warmup" "${extra[@]}" \
                --out "$work/$name-$side-$r" >"$work/$name-$side-$r.log"
        done
    done
done
first="$(ls -d "$work"/*-after-1 | head -1)/timings.json"
device="$("$PYTHON" -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"])' "$first")"
out="benchmarks/results/$(device_slug "$first")-$size-$label-ab.md"
"$PYTHON" - "$work" "$repeats" "$out" "$device" "$size" "$frames" "$warmup" "${extra[*]:-}" <<'PY'
import glob, json, os, statistics, sys
work, repeats, out, device, size, frames, warmup, extra = sys.argv[1:]
names = sorted({os.path.basename(p).rsplit('-', 2)[0] for p in glob.glob(f'{work}/*-after-1')})
lines = [f'Device: {device}; `vct render --size {size} --frames {frames} --warmup {warmup} {extra}`; before and after '
         f'alternated {repeats}x; per pass the median over the runs of each run\'s median (ms).', '']
for name in names:
    rows = {}
    for side in ('before', 'after'):
        for r in range(1, int(repeats) + 1):
            j = json.load(open(f'{work}/{name}-{side}-{r}/timings.json'))
            for p in j['passes']:
                rows.setdefault(p['name'], {}).setdefault(side, []).append(p['median_ms'])
            rows.setdefault('frame', {}).setdefault(side, []).append(j['frame_median_ms'])
    lines += [f'**{name}**', '', '| pass | before | after | after / before |', '| --- | ---: | ---: | ---: |']
    for k, v in rows.items():
        b = statistics.median(v.get('before', [0])); a = statistics.median(v.get('after', [0]))
        lines.append(f'| {k} | {b:.2f} | {a:.2f} | {a / b if b else float("nan"):.3f} |')
    lines.append('')
open(out, 'w').write('\n'.join(lines))
print('\n'.join(lines))
print('wrote', out)
PY
rm -rf "$work"
