#!/usr/bin/env python3
"""An open plane under the default sky, for measuring how the cones read the environment (benchmarks/README.md,
round 27): a 40 m square at y = 0 of one material (base colour 0.9, the metallic and roughness given), a camera 3 m
above it looking down 35 degrees along -z, and a directional light of 3 lux along (-0.3, -1, -0.6) (the loader's
default light), so that vct and its reference both light it with the procedural sky of that sun. Nothing but the
plane occludes the sky: its indirect light is the sky's, seen through the material's lobes.

Usage:
  open_plane.py OUT.gltf METALLIC ROUGHNESS

Example (a rough dielectric, one bounce, against the path tracer):
  benchmarks/open_plane.py /tmp/plane.gltf 0 0.6
  TRUTH_REFERENCES=1 TRUTH_VOXELS=64 TRUTH_SCALES=4 benchmarks/truth.sh /tmp/plane.gltf
"""
import base64
import json
import math
import struct
import sys


def axis_angle(axis, angle):
    s = math.sin(angle / 2.0)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2.0)]


def multiply(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def plane(metallic, roughness):
    half = 20.0
    positions = [-half, 0, -half, half, 0, -half, half, 0, half, -half, 0, half]
    normals = [0, 1, 0] * 4
    indices = [0, 2, 1, 0, 3, 2]
    data = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<6H", *indices) + b"\0\0"
    # The light shines along its local -z: turn -z onto the light's direction (yaw about +y, then pitch about +x).
    d = [-0.3, -1.0, -0.6]
    length = math.sqrt(sum(x * x for x in d))
    d = [x / length for x in d]
    light = multiply(axis_angle([0, 1, 0], math.atan2(-d[0], -d[2])), axis_angle([1, 0, 0], math.asin(d[1])))
    return {
        "asset": {"version": "2.0", "generator": "vct benchmarks/open_plane.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}},
        "nodes": [
            {"mesh": 0, "name": "plane"},
            {"camera": 0, "translation": [0, 3, 6], "rotation": axis_angle([1, 0, 0], math.radians(-35))},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": light},
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 200, "aspectRatio": 16 / 9}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "m%.2f_r%.2f" % (metallic, roughness),
                       "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1],
                                                "metallicFactor": metallic, "roughnessFactor": roughness}}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-half, 0, -half], "max": [half, 0, half]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    try:
        metallic, roughness = float(sys.argv[2]), float(sys.argv[3])
    except ValueError:
        sys.exit("open_plane.py: METALLIC and ROUGHNESS must be numbers")
    if not (0.0 <= metallic <= 1.0 and 0.0 <= roughness <= 1.0):
        sys.exit("open_plane.py: METALLIC and ROUGHNESS must lie in [0, 1]")
    with open(sys.argv[1], "w") as out:
        json.dump(plane(metallic, roughness), out)


if __name__ == "__main__":
    main()
