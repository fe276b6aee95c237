#!/usr/bin/env python3
"""Makes the blended-surfaces benchmark scene from scenes/cornell.glb: the gold sphere, the tall box and the
moving cube get alphaMode BLEND materials of their own (alpha 0.5, 0.4, 0.6; the room keeps its opaque ones),
so the blend pass draws three instances, one of them moving, over the opaque room.

    benchmarks/blend_scene.py scenes/cornell.glb OUT.glb
"""
import copy
import json
import struct
import sys

ALPHAS = {"sphere": 0.5, "tall box": 0.4, "cube": 0.6}


def main(source, target):
    data = open(source, "rb").read()
    magic, version, _ = struct.unpack("<III", data[:12])
    json_length, json_type = struct.unpack("<II", data[12:20])
    assert magic == 0x46546C67 and json_type == 0x4E4F534A, "not a glb with a JSON chunk first"
    doc = json.loads(data[20:20 + json_length])
    rest = data[20 + json_length:]  # the BIN chunk, unchanged
    for mesh in doc["meshes"]:
        alpha = ALPHAS.get(mesh.get("name"))
        if alpha is None:
            continue
        for primitive in mesh["primitives"]:
            material = copy.deepcopy(doc["materials"][primitive["material"]])
            material["name"] = material.get("name", "material") + " (blended)"
            pbr = material.setdefault("pbrMetallicRoughness", {})
            pbr["baseColorFactor"] = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3] + [alpha]
            material["alphaMode"] = "BLEND"
            doc["materials"].append(material)
            primitive["material"] = len(doc["materials"]) - 1
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    out = struct.pack("<III", magic, version, 12 + 8 + len(text) + len(rest))
    out += struct.pack("<II", len(text), json_type) + text + rest
    open(target, "wb").write(out)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
