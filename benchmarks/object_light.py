#!/usr/bin/env python3
"""The tables of benchmarks/object_light.sh, as Markdown on stdout.

Usage: object_light.py WORK SCENE MATERIAL SIZE SPP FRAMES VOXELS...
WORK holds truth-{whole,absorb,glow}-N.json (`vct compare --reference-dir` of each variant at N³ voxels) and the
renders vct-VARIANT-N/ (their timings.json names the device). Per surface and part (indirect, diffuse, specular),
vct ÷ truth of:
  whole    the scene as it is;
  absorb   the scene with the object reflecting nothing: everything's light but the object's;
  object   the object's own light: (whole − absorb) in vct over the same difference in the truth;
  glow     the object glowing with radiance 1 and no lights: the share of a uniform emitter each surface gathers.
"""
import json
import os
import sys

PARTS = ('indirect', 'diffuse', 'specular')


def load(work, variant, n):
    with open(os.path.join(work, f'truth-{variant}-{n}.json')) as f:
        return {s['name']: s for s in json.load(f)['surfaces']}


def ratio(vct, reference):
    return vct / reference if reference > 0 else float('nan')


def main(argv):
    if len(argv) < 8:
        sys.exit(__doc__)
    work, scene, material, size, spp, frames = argv[1:7]
    voxels = argv[7:]
    data = {(v, n): load(work, v, n) for v in ('whole', 'absorb', 'glow') for n in voxels}
    with open(os.path.join(work, f'vct-whole-{voxels[0]}', 'timings.json')) as f:
        device = json.load(f)['device']
    surfaces = list(data[('whole', voxels[0])].keys())
    print(f'# The light of `{material}` in `{scene}` against the path-traced truth\n')
    print(f'Device: {device}. `benchmarks/object_light.sh`: {size}, {frames} frames (the last measured), trace '
          f'scale 4, one bounce; one-bounce references of {spp} spp per variant at the same frame. vct ÷ truth per '
          f'surface, sums over the surface\'s pixels of the demodulated light:\n'
          f'- **whole**: the scene as it is;\n'
          f'- **absorb**: `{material}` reflects nothing (black, metallic 1), still occluding: everything\'s light '
          f'but its own;\n'
          f'- **object**: `{material}`\'s own light, whole − absorb in vct over the same in the truth; **share**: '
          f'that light\'s part of the truth\'s whole;\n'
          f'- **glow**: no lights, `{material}` glowing with radiance 1: the cones\' geometry alone.\n\n'
          f'The surfaces of `{material}` itself are left out.\n')
    for part in PARTS:
        print(f'## {part}\n')
        header = ['surface', 'share']
        for label in ('whole', 'absorb', 'object', 'glow'):
            header += [f'{label} {n}³' for n in voxels]
        print('| ' + ' | '.join(header) + ' |')
        print('|' + '---|' * len(header))
        for name in surfaces:
            if name.endswith('/' + material):
                continue  # the object itself: its own light on itself is not measured
            whole_ref = data[('whole', voxels[0])][name][part]['reference_sum']
            absorb_ref = data[('absorb', voxels[0])][name][part]['reference_sum']
            if whole_ref <= 0:
                continue
            def cell(label, n):
                return data[(label, n)][name][part]

            row = [name, f'{(whole_ref - absorb_ref) / whole_ref:.3f}']
            row += [f"{cell('whole', n)['ratio']:.3f}" for n in voxels]
            row += [f"{cell('absorb', n)['ratio']:.3f}" for n in voxels]
            row += [f"{ratio(cell('whole', n)['vct_sum'] - cell('absorb', n)['vct_sum'], whole_ref - absorb_ref):.3f}"
                    for n in voxels]
            row += [f"{cell('glow', n)['ratio']:.3f}" for n in voxels]
            print('| ' + ' | '.join(row) + ' |')
        print()


if __name__ == '__main__':
    main(sys.argv)
