#!/usr/bin/env python3
"""Converts a PLY (ASCII or binary little-endian) or OBJ mesh to glTF: binary (.glb) or
JSON with the buffer embedded (.gltf), by the output's extension; one mesh node, float32
POSITION, uint32 indices, one default material, no camera (gridrt frames the scene itself).

    tools/mesh_to_gltf.py bunny.ply bunny.glb
    tools/mesh_to_gltf.py teapot.obj teapot.gltf

Polygons are triangulated as fans (v0, vi, vi+1). OBJ: only `v` and `f` lines are read
(`f` corners may be v, v/vt, v//vn or v/vt/vn; negative indices count back from the
latest vertex). PLY: the `vertex` element's x, y, z and the `face` element's
vertex_indices (or vertex_index) list; other elements and properties are skipped.
Standard library only.
"""
import base64
import json
import struct
import sys

# PLY scalar types -> struct format characters (little-endian).
PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B",
    "short": "h", "int16": "h", "ushort": "H", "uint16": "H",
    "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


class MeshError(Exception):
    pass


# ------------------------------------------------------------------------------------------
# PLY

def read_ply_header(data):
    """Returns (format, elements, body offset); elements = [(name, count, [properties])],
    a property being (name, type) or (name, ("list", count_type, item_type))."""
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshError("not a PLY file (no 'ply' magic or no 'end_header')")
    body = data.index(b"\n", end) + 1
    fmt, elements = None, []
    for raw in data[:end].decode("ascii", "replace").splitlines()[1:]:
        words = raw.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1][2].append((words[4], ("list", words[2], words[3])))
            else:
                elements[-1][2].append((words[2], words[1]))
    if fmt not in ("ascii", "binary_little_endian"):
        raise MeshError("unsupported PLY format '%s' (ascii or binary_little_endian)" % fmt)
    for _, _, props in elements:
        for name, kind in props:
            types = kind[1:] if isinstance(kind, tuple) else (kind,)
            for t in types:
                if t not in PLY_TYPES:
                    raise MeshError("unsupported PLY type '%s' of property '%s'" % (t, name))
    return fmt, elements, body


class BinaryReader:
    def __init__(self, data, offset):
        self.data, self.offset = data, offset

    def read(self, ply_type):
        code = "<" + PLY_TYPES[ply_type]
        size = struct.calcsize(code)
        if self.offset + size > len(self.data):
            raise MeshError("PLY data ends early at byte %d" % self.offset)
        value = struct.unpack_from(code, self.data, self.offset)[0]
        self.offset += size
        return value


class AsciiReader:
    def __init__(self, data, offset):
        self.words = iter(data[offset:].decode("ascii", "replace").split())

    def read(self, ply_type):
        try:
            word = next(self.words)
        except StopIteration:
            raise MeshError("PLY data ends early")
        return float(word) if PLY_TYPES[ply_type] in "fd" else int(word)


def read_ply(data):
    fmt, elements, body = read_ply_header(data)
    reader = AsciiReader(data, body) if fmt == "ascii" else BinaryReader(data, body)
    positions, faces = [], []
    for name, count, props in elements:
        for _ in range(count):
            values = {}
            for prop, kind in props:
                if isinstance(kind, tuple):
                    n = int(reader.read(kind[1]))
                    values[prop] = [int(reader.read(kind[2])) for _ in range(n)]
                else:
                    values[prop] = reader.read(kind)
            if name == "vertex":
                try:
                    positions.append((float(values["x"]), float(values["y"]), float(values["z"])))
                except KeyError:
                    raise MeshError("PLY vertex element lacks x, y or z")
            elif name == "face":
                polygon = values.get("vertex_indices", values.get("vertex_index"))
                if polygon is None:
                    raise MeshError("PLY face element lacks vertex_indices")
                faces.append(polygon)
    return positions, faces


# ------------------------------------------------------------------------------------------
# OBJ

def read_obj(data):
    positions, faces = [], []
    for number, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            try:
                positions.append(tuple(float(w) for w in words[1:4]))
            except ValueError:
                raise MeshError("line %d: bad vertex '%s'" % (number, line.strip()))
            if len(positions[-1]) != 3:
                raise MeshError("line %d: a vertex needs x y z" % number)
        elif words[0] == "f":
            polygon = []
            for corner in words[1:]:
                try:
                    i = int(corner.split("/")[0])
                except ValueError:
                    raise MeshError("line %d: bad face corner '%s'" % (number, corner))
                # 1-based; negative counts back from the latest vertex.
                index = i - 1 if i > 0 else len(positions) + i
                if i == 0 or not 0 <= index < len(positions):
                    raise MeshError("line %d: vertex index %d out of range" % (number, i))
                polygon.append(index)
            faces.append(polygon)
    return positions, faces


# ------------------------------------------------------------------------------------------
# glTF

def fan_triangles(faces, vertex_count):
    indices = []
    for number, polygon in enumerate(faces):
        for v in polygon:
            if not 0 <= v < vertex_count:
                raise MeshError("face %d: vertex index %d out of range" % (number, v))
        for k in range(1, len(polygon) - 1):
            indices += (polygon[0], polygon[k], polygon[k + 1])
    return indices


def pad4(blob, byte):
    return blob + byte * (-len(blob) % 4)


def make_gltf(positions, indices):
    """The glTF document and its binary buffer (positions, then uint32 indices)."""
    if not indices:
        raise MeshError("the mesh has no triangles")
    pos_blob = b"".join(struct.pack("<3f", *p) for p in positions)
    idx_blob = struct.pack("<%dI" % len(indices), *indices)
    binary = pad4(pos_blob, b"\0") + idx_blob
    lo = [min(p[a] for p in positions) for a in range(3)]
    hi = [max(p[a] for p in positions) for a in range(3)]
    # min/max as float32 values, as the spec asks of POSITION bounds.
    lo = list(struct.unpack("<3f", struct.pack("<3f", *lo)))
    hi = list(struct.unpack("<3f", struct.pack("<3f", *hi)))
    doc = {
        "asset": {"version": "2.0", "generator": "gridrt tools/mesh_to_gltf.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "mesh"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                    "material": 0, "mode": 4}]}],
        "materials": [{"name": "default",
                       "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0],
                                                "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos_blob), "target": 34962},
            {"buffer": 0, "byteOffset": len(pad4(pos_blob, b"\0")), "byteLength": len(idx_blob),
             "target": 34963}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    }
    return doc, binary


def make_glb(positions, indices):
    """Binary glTF: the JSON chunk, then the buffer as the BIN chunk."""
    doc, binary = make_gltf(positions, indices)
    text = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    binary = pad4(binary, b"\0")
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(text), b"JSON") +
            text + struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def make_json_gltf(positions, indices):
    """glTF JSON with the buffer embedded as a base64 data URI (one file, like the .glb)."""
    doc, binary = make_gltf(positions, indices)
    doc["buffers"][0]["uri"] = ("data:application/octet-stream;base64," +
                                base64.b64encode(binary).decode("ascii"))
    return json.dumps(doc, separators=(",", ":")).encode()


def convert(source, target):
    with open(source, "rb") as f:
        data = f.read()
    if data.startswith(b"ply"):
        positions, faces = read_ply(data)
    elif source.lower().endswith(".obj"):
        positions, faces = read_obj(data)
    else:
        raise MeshError("unknown mesh format (PLY needs the 'ply' magic, OBJ the .obj extension)")
    indices = fan_triangles(faces, len(positions))
    if target.lower().endswith(".gltf"):
        out = make_json_gltf(positions, indices)
    elif target.lower().endswith(".glb"):
        out = make_glb(positions, indices)
    else:
        raise MeshError("the output must be .glb (binary glTF) or .gltf (glTF JSON), got '%s'"
                        % target)
    with open(target, "wb") as f:
        f.write(out)
    return len(positions), len(indices) // 3


USAGE = "usage: mesh_to_gltf.py INPUT.{ply,obj} OUTPUT.{glb,gltf}"


def main(argv):
    if len(argv) == 2 and argv[1] in ("-h", "--help"):
        print(USAGE)
        print(__doc__)
        return 0
    if len(argv) != 3:
        print(USAGE, file=sys.stderr)
        return 2
    try:
        vertices, triangles = convert(argv[1], argv[2])
    except (OSError, MeshError, ValueError, struct.error) as e:
        print("mesh_to_gltf: %s: %s" % (argv[1], e), file=sys.stderr)
        return 1
    print("mesh_to_gltf: %s -> %s: %d vertices, %d triangles" % (argv[1], argv[2], vertices, triangles))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
