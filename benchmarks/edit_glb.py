#!/usr/bin/env python3
"""Variants of a scene written by `vct export-scene`, for experiments on the cone tracer (benchmarks/README.md,
round 14): the same room without some of its objects, with every material but some black, or with the scene bounds
padded so that the grid fit puts a room's bounding walls mid-voxel.

Usage:
  edit_glb.py drop IN.glb OUT.glb NODE...           without the root nodes named NODE (and their animation channels)
  edit_glb.py black IN.glb OUT.glb KEEP...          every material black (base colour 0) but those named KEEP
  edit_glb.py pad IN.glb OUT.glb MESH HALF DELTA    four copies of mesh MESH, scaled to nothing, at x = ±(HALF +
                                                    DELTA) and z = ±(HALF + DELTA) (y at the bounds' middle is not
                                                    needed: they only widen the bounds)

Example (cornell's room alone, Lambertian, against `vct reference --secondary diffuse`):
  build/vct export-scene --scene cornell --out /tmp/cornell.glb
  benchmarks/edit_glb.py drop /tmp/cornell.glb /tmp/empty.glb "gold sphere" "tall box" "moving cube"
  TRUTH_REFERENCES=diffuse TRUTH_VOXELS="64 128" TRUTH_SCALES=1 TRUTH_FRAMES=8 benchmarks/truth.sh /tmp/empty.glb
The grid fit (lib/voxel.glsl's voxelGridFit) leaves one voxel free at each end of the bounds' longest side, so a
wall on the bounds lies on a voxel face; DELTA = 2 / (N − 3) for a side of 4 puts it mid-voxel at N³.
"""
import json
import struct
import sys


def read(path):
    data = open(path, 'rb').read()
    if data[:4] != b'glTF':
        sys.exit(f'edit_glb.py: {path}: not a binary glTF file')
    length = struct.unpack('<I', data[12:16])[0]
    return json.loads(data[20:20 + length]), data[20 + length:]


def write(path, document, rest):
    text = json.dumps(document).encode()
    text += b' ' * ((4 - len(text) % 4) % 4)
    header = b'glTF' + struct.pack('<II', 2, 12 + 8 + len(text) + len(rest))
    open(path, 'wb').write(header + struct.pack('<I', len(text)) + b'JSON' + text + rest)


def drop(document, names):
    removed = {i for i, node in enumerate(document['nodes']) if node.get('name') in names}
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


def black(document, keep):
    for material in document.get('materials', []):
        if material.get('name') not in keep:
            material.setdefault('pbrMetallicRoughness', {})['baseColorFactor'] = [0.0, 0.0, 0.0, 1.0]


def pad(document, mesh_name, half, delta):
    meshes = [i for i, m in enumerate(document['meshes']) if m.get('name') == mesh_name]
    if not meshes:
        sys.exit(f'edit_glb.py: no mesh named {mesh_name!r}')
    e = half + delta
    for t in ([e, 0.0, 0.0], [-e, 0.0, 0.0], [0.0, 0.0, e], [0.0, 0.0, -e]):
        document['nodes'].append({'name': 'pad', 'mesh': meshes[0], 'translation': t, 'scale': [1e-3] * 3})
        document['scenes'][0]['nodes'].append(len(document['nodes']) - 1)


def main(argv):
    if len(argv) < 4 or argv[1] not in ('drop', 'black', 'pad'):
        sys.exit(__doc__)
    command, source, target, args = argv[1], argv[2], argv[3], argv[4:]
    document, rest = read(source)
    if command == 'drop':
        drop(document, set(args))
    elif command == 'black':
        black(document, set(args))
    else:
        if len(args) != 3:
            sys.exit(__doc__)
        pad(document, args[0], float(args[1]), float(args[2]))
    write(target, document, rest)


if __name__ == '__main__':
    main(sys.argv)
