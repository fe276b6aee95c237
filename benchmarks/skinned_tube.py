#!/usr/bin/env python3
"""Writes a synthetic skinned mesh for the skin pass's cost (benchmarks/results/*-skin.md): a tube of RINGS x
SEGMENTS vertices (default 400 x 256 = 102 400 vertices, 204 288 triangles) bent by JOINTS joints in a chain
along its axis, each joint's rotation about z animated (LINEAR, 2 s loop), every vertex weighted between its
two nearest joints. With --rigid the same tube has no skin and its node turns instead (a rigidly moving
instance of the same size: the A/B without deformation). A directional light and a camera are included.

    python3 benchmarks/skinned_tube.py OUT_DIR [--rings N] [--segments N] [--joints N] [--rigid]
writes OUT_DIR/tube.gltf (tube_rigid.gltf with --rigid) and its .bin.
"""
import argparse
import json
import math
import os
import struct

parser = argparse.ArgumentParser()
parser.add_argument("out")
parser.add_argument("--rings", type=int, default=400)
parser.add_argument("--segments", type=int, default=256)
parser.add_argument("--joints", type=int, default=4)
parser.add_argument("--rigid", action="store_true")
args = parser.parse_args()

height, radius = 4.0, 0.3
rings, segments, joints = args.rings, args.segments, args.joints
positions, normals, joint_data, weight_data, indices = [], [], [], [], []
for r in range(rings):
    y = height * r / (rings - 1)
    # Position along the chain in joint units: between joint j and j + 1.
    u = min(max(y / height * (joints - 1), 0.0), joints - 1 - 1e-6)
    j = int(u)
    f = u - j
    for s in range(segments):
        a = 2 * math.pi * s / segments
        positions += [radius * math.cos(a), y, radius * math.sin(a)]
        normals += [math.cos(a), 0.0, math.sin(a)]
        joint_data += [j, j + 1, 0, 0]
        weight_data += [1.0 - f, f, 0.0, 0.0]
for r in range(rings - 1):
    for s in range(segments):
        a, b = r * segments + s, r * segments + (s + 1) % segments
        c, d = a + segments, b + segments
        indices += [a, c, b, b, c, d]

blob = bytearray()
views, accessors = [], []


def add(data, fmt, component, count, kind, extra=None):
    while len(blob) % 4:
        blob.append(0)
    offset = len(blob)
    blob.extend(struct.pack("<%d%s" % (len(data), fmt), *data))
    views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset})
    accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
    accessor.update(extra or {})
    accessors.append(accessor)
    return len(accessors) - 1


n = rings * segments
attributes = {
    "POSITION": add(positions, "f", 5126, n, "VEC3", {"min": [-radius, 0, -radius], "max": [radius, height, radius]}),
    "NORMAL": add(normals, "f", 5126, n, "VEC3"),
}
index_accessor = add(indices, "I", 5125, len(indices), "SCALAR")
times = add([0.0, 1.0, 2.0], "f", 5126, 3, "SCALAR")
angle = 0.35  # radians per joint at t = 1 s
quat = [0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)]
rotations = add([0, 0, 0, 1] + quat + [0, 0, 0, 1], "f", 5126, 3, "VEC4")
nodes = [{"name": "tube", "mesh": 0}]
animation_channels = []
if args.rigid:
    animation_channels.append({"sampler": 0, "target": {"node": 0, "path": "rotation"}})
    scene_nodes = [0]
else:
    attributes["JOINTS_0"] = add(joint_data, "H", 5123, n, "VEC4")
    attributes["WEIGHTS_0"] = add(weight_data, "f", 5126, n, "VEC4")
    nodes[0]["skin"] = 0
    inverse_bind = []
    for j in range(joints):
        y = height * j / (joints - 1)
        inverse_bind += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -y, 0, 1]
        node = {"name": "joint %d" % j, "translation": [0, y if j == 0 else height / (joints - 1), 0]}
        if j + 1 < joints:
            node["children"] = [len(nodes) + 1]
        nodes.append(node)
        animation_channels.append({"sampler": 0, "target": {"node": len(nodes) - 1, "path": "rotation"}})
    ibm = add(inverse_bind, "f", 5126, joints, "MAT4")
    skins = [{"joints": list(range(1, joints + 1)), "inverseBindMatrices": ibm}]
    scene_nodes = [0, 1]
nodes.append({"name": "camera", "camera": 0, "translation": [0, 2, 7]})
nodes.append({"name": "sun", "rotation": [-0.3826834, 0.0, 0.0, 0.9238795],
              "extensions": {"KHR_lights_punctual": {"light": 0}}})
scene_nodes += [len(nodes) - 2, len(nodes) - 1]
doc = {
    "asset": {"version": "2.0", "generator": "benchmarks/skinned_tube.py"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}},
    "scene": 0,
    "scenes": [{"nodes": scene_nodes}],
    "nodes": nodes,
    "meshes": [{"name": "tube", "primitives": [{"attributes": attributes, "indices": index_accessor, "material": 0}]}],
    "materials": [{"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1], "metallicFactor": 0,
                                                           "roughnessFactor": 0.6}}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100}}],
    "animations": [{"name": "bend", "samplers": [{"input": times, "output": rotations, "interpolation": "LINEAR"}],
                    "channels": animation_channels}],
    "buffers": [{"uri": "tube.bin", "byteLength": len(blob)}],
    "bufferViews": views,
    "accessors": accessors,
}
if not args.rigid:
    doc["skins"] = skins
os.makedirs(args.out, exist_ok=True)
name = "tube_rigid" if args.rigid else "tube"
doc["buffers"][0]["uri"] = name + ".bin"
with open(os.path.join(args.out, name + ".bin"), "wb") as f:
    f.write(blob)
with open(os.path.join(args.out, name + ".gltf"), "w") as f:
    json.dump(doc, f)
print("wrote %s/%s.gltf: %d vertices, %d triangles" % (args.out, name, n, len(indices) // 3))
