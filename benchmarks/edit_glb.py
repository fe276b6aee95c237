#!/usr/bin/env python3
"""Variants of a scene written by `vct export-scene`, for experiments on the cone tracer (benchmarks/README.md,
round 14): the same room without some of its objects, with every material but some black, or with the scene bounds
padded so that the grid fit puts a room's bounding walls mid-voxel.

Usage:
  edit_glb.py drop IN.glb OUT.glb NODE...           without the root nodes named NODE (and their animation channels)
  edit_glb.py black IN.glb OUT.glb KEEP...          every material's base colour black but those named KEEP
                                                    (emission and the dielectric F0 stay: with --voxel-glossy off
                                                    and a --secondary diffuse reference they light nothing)
  edit_glb.py absorb IN.glb OUT.glb MATERIAL...    the materials named MATERIAL reflect nothing: base colour black,
                                                    metallic 1 (F0 = the base colour: 0); they still occlude
  edit_glb.py glow IN.glb OUT.glb MATERIAL...      no punctual lights; the materials named MATERIAL emit radiance 1
                                                    (emissiveFactor 1, 1, 1): a uniformly glowing object whose light
                                                    reaching the others tests the cones' geometry alone
  edit_glb.py pad IN.glb OUT.glb MESH HALF DELTA    four nodes of mesh MESH scaled to 1/1000, at x = ±(HALF + DELTA)
                                                    and z = ±(HALF + DELTA), y = 0, in the first scene: they widen
                                                    the bounds of a room centred on x = z = 0 whose walls stand at
                                                    x, z = ±HALF (cornell: 2)
  edit_glb.py turn IN.glb OUT.glb X Y Z DEGREES     the whole first scene (camera and lights too) turned DEGREES about
                                                    the axis (X, Y, Z) through the origin: a room off the grid's axes,
                                                    the same light (docs/design.md §5.6)
A name that matches nothing is an error.

Example (cornell's room alone, Lambertian, against `vct reference --secondary diffuse`):
  build/vct export-scene --scene cornell --out /tmp/cornell.glb
  benchmarks/edit_glb.py drop /tmp/cornell.glb /tmp/empty.glb "gold sphere" "tall box" "moving cube"
  TRUTH_REFERENCES=diffuse TRUTH_VOXELS="64 128" TRUTH_SCALES=1 TRUTH_FRAMES=8 benchmarks/truth.sh /tmp/empty.glb
The grid fit (lib/voxel.glsl's voxelGridFit) gives the bounds' longest side S to N − 2 voxels, one voxel free at each
end, so a wall on the bounds lies on a voxel face. Padded by DELTA at each end, the voxel is (S + 2·DELTA)/(N − 2)
and the wall lies (1 + DELTA/voxel) voxels from the grid's edge: mid-voxel for DELTA = S / (2(N − 3)), i.e.
2 / (N − 3) for cornell's S = 4. Each grid size needs its own file.
"""
import json
import struct
import sys


def read(path):
    data = open(path, 'rb').read()
    if data[:4] != b'glTF':
        sys.exit(f'edit_glb.py: {path}: not a binary glTF file')
    length, kind = struct.unpack('<I4s', data[12:20])
    if kind != b'JSON':
        sys.exit(f'edit_glb.py: {path}: the first chunk is not JSON')
    return json.loads(data[20:20 + length]), data[20 + length:]


def write(path, document, rest):
    text = json.dumps(document).encode()
    text += b' ' * ((4 - len(text) % 4) % 4)
    header = b'glTF' + struct.pack('<II', 2, 12 + 8 + len(text) + len(rest))
    open(path, 'wb').write(header + struct.pack('<I', len(text)) + b'JSON' + text + rest)


def drop(document, names):
    removed = {i for i, node in enumerate(document['nodes']) if node.get('name') in names}
    missing = names - {document['nodes'][i].get('name') for i in removed}
    if missing:
        sys.exit(f'edit_glb.py: no node named {", ".join(sorted(missing))}')
    for scene in document['scenes']:
        scene['nodes'] = [n for n in scene['nodes'] if n not in removed]
    animations = []
    for animation in document.get('animations', []):
        animation['channels'] = [c for c in animation['channels'] if c['target'].get('node') not in removed]
        if animation['channels']:
            animations.append(animation)
    if animations:
        document['animations'] = animations
    else:
        document.pop('animations', None)


def named_materials(document, names):
    # The materials named `names`; exits naming those that match none.
    materials = [m for m in document.get('materials', []) if m.get('name') in names]
    missing = names - {m.get('name') for m in materials}
    if missing:
        sys.exit(f'edit_glb.py: no material named {", ".join(sorted(missing))}')
    return materials


def black(document, keep):
    named_materials(document, keep)  # every name must match one
    for material in document.get('materials', []):
        if material.get('name') not in keep:
            material.setdefault('pbrMetallicRoughness', {})['baseColorFactor'] = [0.0, 0.0, 0.0, 1.0]


def absorb(document, names):
    for material in named_materials(document, names):
        pbr = material.setdefault('pbrMetallicRoughness', {})
        pbr['baseColorFactor'] = [0.0, 0.0, 0.0, 1.0]
        pbr['metallicFactor'] = 1.0


def glow(document, names):
    for material in named_materials(document, names):
        material['emissiveFactor'] = [1.0, 1.0, 1.0]
    for node in document.get('nodes', []):
        node.get('extensions', {}).pop('KHR_lights_punctual', None)


def pad(document, mesh_name, half, delta):
    meshes = [i for i, m in enumerate(document['meshes']) if m.get('name') == mesh_name]
    if not meshes:
        sys.exit(f'edit_glb.py: no mesh named {mesh_name!r}')
    e = half + delta
    for t in ([e, 0.0, 0.0], [-e, 0.0, 0.0], [0.0, 0.0, e], [0.0, 0.0, -e]):
        document['nodes'].append({'name': 'pad', 'mesh': meshes[0], 'translation': t, 'scale': [1e-3] * 3})
        document['scenes'][0]['nodes'].append(len(document['nodes']) - 1)


def turn(document, axis, degrees):
    import math
    length = math.sqrt(sum(a * a for a in axis))
    if length == 0.0:
        sys.exit('edit_glb.py: turn: the axis is zero')
    half = math.radians(degrees) / 2.0
    q = [a / length * math.sin(half) for a in axis] + [math.cos(half)]  # glTF order: x, y, z, w
    scene = document['scenes'][0]
    document['nodes'].append({'name': 'turn', 'rotation': q, 'children': scene['nodes']})
    scene['nodes'] = [len(document['nodes']) - 1]


def main(argv):
    if len(argv) < 4 or argv[1] not in ('drop', 'black', 'absorb', 'glow', 'pad', 'turn'):
        sys.exit(__doc__)
    command, source, target, args = argv[1], argv[2], argv[3], argv[4:]
    document, rest = read(source)
    if command == 'drop':
        drop(document, set(args))
    elif command == 'black':
        black(document, set(args))
    elif command == 'absorb':
        absorb(document, set(args))
    elif command == 'glow':
        glow(document, set(args))
    elif command == 'turn':
        if len(args) != 4:
            sys.exit(__doc__)
        turn(document, [float(a) for a in args[:3]], float(args[3]))
    else:
        if len(args) != 3:
            sys.exit(__doc__)
        pad(document, args[0], float(args[1]), float(args[2]))
    write(target, document, rest)


if __name__ == '__main__':
    main(sys.argv)
