#!/usr/bin/env bash
# Sparse voxel storage (docs/design.md §5.10): memory and per-pass GPU medians of `vct render` at each voxel
# resolution on cornell and the hall (their moving objects update their bricks every frame), the default
# configuration otherwise. Writes benchmarks/results/<device>-sparse-voxels.md.
# Usage: benchmarks/sparse_voxels.sh   (SV_SIZE [640x360], SV_FRAMES [30], SV_WARMUP [5], SV_GRIDS ["64 128 256"])
set -euo pipefail
source "$(dirname "$0")/common.sh"
vct="${VCT:-build/vct}"
size="${SV_SIZE:-640x360}" frames="${SV_FRAMES:-30}" warmup="${SV_WARMUP:-5}" grids="${SV_GRIDS:-64 128 256}"
work="$(mktemp -d)"
for scene in cornell hall; do
    for n in $grids; do
        "$vct" render --scene "$scene" --size "$size" --frames "$frames" --warmup "$warmup" --voxels "$n" \
            --out "$work/$scene-$n" >"$work/$scene-$n.log"
    done
done
first="$(ls -d "$work"/*/ | head -1)timings.json"
out="benchmarks/results/$(device_slug "$first")-sparse-voxels.md"
"$PYTHON" - "$work" "$out" "$size" "$frames" "$warmup" "$grids" <<'PY'
import json, sys
work, out, size, frames, warmup, grids = sys.argv[1:]
lines = []
passes = ['voxelize', 'inject', 'mips', 'bounce', 'trace', 'resample', 'frame']
for scene in ('cornell', 'hall'):
    lines += [f'**{scene}**', '',
              '| N | bricks | share | memory (MiB) | dense (MiB) | memory / dense | mip 0 | ' +
              ' | '.join(passes) + ' |', '| ---: ' * 6 + '| --- ' + '| ---: ' * len(passes) + '|']
    for n in grids.split():
        j = json.load(open(f'{work}/{scene}-{n}/timings.json'))
        v = j['voxel_storage']
        median = {p['name']: p['median_ms'] for p in j['passes']}
        median['frame'] = j['frame_median_ms']
        sparse = int(n) >= j['settings'].get('sparse-mip0-from', 256)
        lines.append(f"| {n} | {v['bricks']} of {v['brick_slots']} | {100 * v['bricks'] / v['brick_slots']:.1f} % | "
                     f"{v['bytes'] / 2**20:.1f} | {v['dense_bytes'] / 2**20:.1f} | "
                     f"{100 * v['bytes'] / v['dense_bytes']:.1f} % | {'sparse' if sparse else 'dense'} | " +
                     ' | '.join(f"{median.get(p, 0.0):.2f}" for p in passes) + ' |')
    lines.append('')
device = json.load(open(f'{work}/cornell-{grids.split()[0]}/timings.json'))['device']
text = (f'Device: {device}. `vct render --size {size} --frames {frames} --warmup {warmup} --voxels N`, default '
        f'settings otherwise (trace scale 4, sg + adaptive, all bounces); per-pass GPU medians in ms over the timed '
        f'frames (the moving object updates its bricks every frame). Memory: the grid\'s device memory against '
        f'dense N³ storage of the same data (`voxel_storage` in timings.json).\n\n' + '\n'.join(lines))
open(out, 'w').write(text)
print(text)
print('wrote', out)
PY
rm -rf "$work"
