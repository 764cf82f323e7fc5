"""The scene as the workers get it: the .gltf/.glb and the files it names by relative URI
(buffers, images), read here and shipped with the tasks; and the image size a scene's
camera gives when neither --width nor --height is given."""
import json
import math
import os
import struct
import urllib.parse

from .worker_task import bundle_digest

GLB_MAGIC = b"glTF"
GLB_JSON_CHUNK = 0x4E4F534A  # "JSON", little-endian
DEFAULT_WIDTH, DEFAULT_HEIGHT = 640, 480  # gridrt's defaults
MAX_SIZE = 65536


class SceneError(Exception):
    """The scene cannot be read here: one line, exit 1."""


def gltf_json(data):
    """The glTF JSON of a .gltf or .glb's bytes, or None when it is neither (gridrt then
    says what is wrong with it)."""
    try:
        if data[:4] == GLB_MAGIC:
            length, kind = struct.unpack_from("<II", data, 12)
            if kind != GLB_JSON_CHUNK:
                return None
            return json.loads(data[20:20 + length].decode("utf-8"))
        return json.loads(data.decode("utf-8"))
    except (ValueError, UnicodeDecodeError, struct.error):
        return None


def referenced_files(document):
    """The relative URIs of the scene's buffers and images (data: URIs are inside)."""
    names = []
    for key in ("buffers", "images"):
        for item in (document or {}).get(key, []) if isinstance(document, dict) else []:
            uri = item.get("uri") if isinstance(item, dict) else None
            if isinstance(uri, str) and not uri.startswith("data:") and "://" not in uri:
                names.append(urllib.parse.unquote(uri))
    return names


class SceneBundle:
    """The files of a scene, by their path relative to the scene's folder, and a digest that
    names them on the workers (each keeps one copy per digest)."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as e:
            raise SceneError(f"cannot read scene '{path}': {e.strerror}") from None
        self.document = gltf_json(data)
        self.files = {os.path.basename(path): data}
        folder = os.path.dirname(os.path.abspath(path))
        for name in referenced_files(self.document):
            if os.path.isabs(name) or ".." in name.replace("\\", "/").split("/"):
                raise SceneError(f"scene '{path}' names '{name}' outside its folder: "
                                 "use --shared-scene")
            try:
                with open(os.path.join(folder, name), "rb") as f:
                    self.files[name] = f.read()
            except OSError:
                pass  # gridrt reports the missing file, as it would alone
        self.digest = bundle_digest(self.files)
        self.main = os.path.basename(path)

    def nbytes(self):
        return sum(len(d) for d in self.files.values())


def camera_widths(document):
    """The widths gridrt would give the image from the scene's perspective cameras'
    aspectRatio at the default height (application.cpp sizedForCamera: the aspect as a
    float, lround(480 * aspect) clamped to 1..65536)."""
    widths = set()
    if not isinstance(document, dict):
        return widths
    for camera in document.get("cameras", []):
        aspect = (camera.get("perspective") or {}).get("aspectRatio") \
            if isinstance(camera, dict) else None
        if isinstance(aspect, (int, float)) and math.isfinite(aspect) and aspect > 0:
            as_float = struct.unpack("<f", struct.pack("<f", float(aspect)))[0]
            width = math.floor(DEFAULT_HEIGHT * as_float + 0.5)
            widths.add(min(max(width, 1), MAX_SIZE))
    return widths
