"""A mesh's triangles read straight from a .glb with numpy, independently of gridrt: the
POSITION and indices accessors of every TRIANGLES primitive of the scene's nodes that
carry no transform, in node order, then primitive order, then index order (the order in
which gridrt numbers triangles, host/scene/gltf_loader.h). Enough for scenes/models'
meshes; anything else raises ValueError."""
import json
import struct

import numpy as np

GLB_MAGIC = 0x46546C67
JSON_CHUNK = 0x4E4F534A
BIN_CHUNK = 0x004E4942
COMPONENT_DTYPES = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
TRIANGLES = 4


def _chunks(data):
    magic, _version, _length = struct.unpack_from("<III", data, 0)
    if magic != GLB_MAGIC:
        raise ValueError("not a .glb file")
    offset, document, binary = 12, None, None
    while offset < len(data):
        size, kind = struct.unpack_from("<II", data, offset)
        body = data[offset + 8:offset + 8 + size]
        if kind == JSON_CHUNK:
            document = json.loads(body)
        elif kind == BIN_CHUNK:
            binary = body
        offset += 8 + size
    return document, binary


def _accessor(document, binary, index, columns):
    accessor = document["accessors"][index]
    view = document["bufferViews"][accessor["bufferView"]]
    if "byteStride" in view or "sparse" in accessor:
        raise ValueError("interleaved or sparse accessors are not read here")
    dtype = COMPONENT_DTYPES[accessor["componentType"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    count = accessor["count"] * columns
    values = np.frombuffer(binary, dtype=dtype, count=count, offset=start)
    return values.reshape(-1, columns) if columns > 1 else values


def read_document(path):
    """(the glTF JSON, the BIN chunk's bytes) of a .glb."""
    return _chunks(open(path, "rb").read())


def read_triangles(path):
    """(vertices, faces): float64 N x 3 positions and int64 M x 3 indices, every
    primitive's vertices appended after the previous ones'."""
    document, binary = read_document(path)
    scene = document["scenes"][document.get("scene", 0)]
    vertices, faces, base = [], [], 0
    for node_index in scene["nodes"]:
        node = document["nodes"][node_index]
        if "mesh" not in node:
            continue
        if any(key in node for key in ("matrix", "translation", "rotation", "scale", "children")):
            raise ValueError("transformed or nested mesh nodes are not read here")
        for primitive in document["meshes"][node["mesh"]]["primitives"]:
            if primitive.get("mode", TRIANGLES) != TRIANGLES or "indices" not in primitive:
                raise ValueError("only indexed TRIANGLES primitives are read here")
            if "extensions" in primitive:
                raise ValueError("compressed primitives are not read here")
            positions = _accessor(document, binary, primitive["attributes"]["POSITION"], 3)
            indices = _accessor(document, binary, primitive["indices"], 1)
            vertices.append(positions.astype(np.float64))
            faces.append(indices.astype(np.int64).reshape(-1, 3) + base)
            base += len(positions)
    return np.concatenate(vertices), np.concatenate(faces)
