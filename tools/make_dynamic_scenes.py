#!/usr/bin/env python3
"""Animated scenes for the benchmarks' dynamic set (tools/bench.py dynamic), made at run time.

    tools/make_dynamic_scenes.py OUTDIR [--sizes 1000,10000,...]

- bunny_spin.glb: the full bunny (scenes/models/bunny.glb, its camera and light) turning
  once a second about its own vertical axis: a node rotation, LINEAR (slerp) through five
  keys 90 degrees apart. Every triangle moves, rigidly.
- wave_N.glb: a square sheet of about N triangles (a regular grid of quads) whose every
  vertex moves every frame: one morph target (a sine bump across the sheet) with its
  weight LINEAR 0 -> 1 -> 0 over a second; a camera looking down at it and a point light.
"""
import argparse
import json
import math
import os
import struct
import sys
from array import array

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FLOAT, UINT = 5126, 5125


def read_glb(path):
    data = open(path, "rb").read()
    json_length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_length])
    offset = 20 + json_length
    bin_length = struct.unpack_from("<I", data, offset)[0]
    return doc, bytearray(data[offset + 8:offset + 8 + bin_length])


def write_glb(path, doc, binary):
    binary = bytes(binary) + b"\0" * (-len(binary) % 4)
    doc["buffers"] = [{"byteLength": len(binary)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def add_accessor(doc, binary, values, gltf_type, component=FLOAT):
    """Appends `values` (floats, or uint32 indices) to the buffer with a view and an accessor."""
    binary.extend(b"\0" * (-len(binary) % 4))
    offset = len(binary)
    raw = array("f" if component == FLOAT else "I", values).tobytes()
    binary.extend(raw)
    doc.setdefault("bufferViews", []).append(
        {"buffer": 0, "byteOffset": offset, "byteLength": len(raw)})
    per = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[gltf_type]
    accessor = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": component,
                "count": len(values) // per, "type": gltf_type}
    if component == FLOAT:
        columns = [values[c::per] for c in range(per)]
        accessor["min"] = [float(min(c)) for c in columns]
        accessor["max"] = [float(max(c)) for c in columns]
    doc.setdefault("accessors", []).append(accessor)
    return len(doc["accessors"]) - 1


def bunny_spin(out):
    doc, binary = read_glb(os.path.join(ROOT, "scenes", "models", "bunny.glb"))
    mesh_nodes = [i for i in doc["scenes"][0]["nodes"] if "mesh" in doc["nodes"][i]]
    lo, hi = doc["accessors"][0]["min"], doc["accessors"][0]["max"]
    centre = [(l + h) / 2 for l, h in zip(lo, hi)]
    # pivot (at the centre, turning) -> offset (back by the centre) -> the bunny's nodes
    doc["nodes"].append({"name": "offset", "translation": [-centre[0], 0, -centre[2]],
                         "children": mesh_nodes})
    doc["nodes"].append({"name": "pivot", "translation": [centre[0], 0, centre[2]],
                         "children": [len(doc["nodes"]) - 1]})
    pivot = len(doc["nodes"]) - 1
    doc["scenes"][0]["nodes"] = [i for i in doc["scenes"][0]["nodes"]
                                 if i not in mesh_nodes] + [pivot]
    angles = [k * math.pi / 2 for k in range(5)]
    keys = [v for a in angles for v in (0, math.sin(a / 2), 0, math.cos(a / 2))]
    t = add_accessor(doc, binary, [k / 4 for k in range(5)], "SCALAR")
    r = add_accessor(doc, binary, keys, "VEC4")
    doc["animations"] = [{"name": "Spin", "samplers": [{"input": t, "output": r}],
                          "channels": [{"sampler": 0,
                                        "target": {"node": pivot, "path": "rotation"}}]}]
    write_glb(out, doc, binary)


def wave(out, triangles):
    n = max(1, round(math.sqrt(triangles / 2)))
    positions, displacement = [], []
    for row in range(n + 1):
        z = -1 + 2 * row / n
        for col in range(n + 1):
            x = -1 + 2 * col / n
            positions += (x, 0.0, z)
            displacement += (0.0, 0.15 * math.sin(3 * math.pi * x) * math.cos(3 * math.pi * z), 0.0)
    quads = []
    for row in range(n):
        for col in range(n):
            a = row * (n + 1) + col
            quads += (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1)
    doc = {"asset": {"version": "2.0", "generator": "tools/make_dynamic_scenes.py"}}
    binary = bytearray()
    p = add_accessor(doc, binary, positions, "VEC3")
    d = add_accessor(doc, binary, displacement, "VEC3")
    idx = add_accessor(doc, binary, quads, "SCALAR", UINT)
    t = add_accessor(doc, binary, [0, 0.5, 1], "SCALAR")
    w = add_accessor(doc, binary, [0, 1, 0], "SCALAR")
    doc.update({
        "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0, "name": "sheet"},
                  {"camera": 0, "translation": [0, 1.6, 2.2],
                   "rotation": [-0.3007, 0, 0, 0.9537]},
                  {"translation": [0.5, 2, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": p}, "indices": idx,
                                    "targets": [{"POSITION": d}]}], "weights": [0]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 8}]}},
        "animations": [{"name": "Wave", "samplers": [{"input": t, "output": w}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}],
    })
    write_glb(out, doc, binary)
    return 2 * n * n


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir")
    p.add_argument("--sizes", default="1000,10000,100000,400000",
                   help="triangles of the wave sheets, comma-separated")
    a = p.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    bunny_spin(os.path.join(a.outdir, "bunny_spin.glb"))
    for size in (int(s) for s in a.sizes.split(",")):
        wave(os.path.join(a.outdir, f"wave_{size}.glb"), size)
    print(f"wrote {a.outdir}")


if __name__ == "__main__":
    sys.exit(main())
