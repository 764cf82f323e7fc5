"""GridRT from Python: the GridRT intersector's ray queries and the command line's renderer.

    import gridrt
    scene = gridrt.load("scenes/models/bunny.glb")        # or gridrt.Scene(vertices, faces)
    hits = scene.intersect(origins, directions)           # hits.t, .prim, .u, .v per ray
    image = gridrt.render("scenes/models/bunny.glb", width=320, height=240, max_depth=2)

render() takes the command line's options by their flag names (max_depth=2 for
--max-depth 2) and returns what its .exr holds. Bad shapes, values and options raise
ValueError, anything else RuntimeError, each with gridrt's one-line message
(docs/python.md).
"""
import math
import warnings as _warnings

import numpy as _np

from . import _gridrt

__all__ = ["Hits", "Scene", "devices", "load", "render"]


def devices():
    """The OpenCL devices, one dict each (id "P:D", name, platform, type, compute_units,
    global_mem_bytes), in the order `gridrt --list-devices` numbers them; device= takes an
    id, a row number or part of a name."""
    return _gridrt.devices()


class Hits:
    """Per ray: t (+inf on a miss), prim (the triangle: the primid AOV's global id for a
    loaded scene, the faces row for a Scene of arrays; -1 on a miss), u and v (the
    barycentrics of the triangle's second and third vertex). The four arrays are views of
    one (N, 4) buffer, `records`."""

    __slots__ = ("records", "t", "prim", "u", "v")

    def __init__(self, records):
        self.records = records
        self.t = records[:, 0]
        self.prim = records.view(_np.int32)[:, 1]
        self.u = records[:, 2]
        self.v = records[:, 3]

    def __len__(self):
        return len(self.t)

    def __repr__(self):
        return f"Hits({len(self)} rays, {int((self.prim >= 0).sum())} hits)"


class Scene:
    """Triangles to query and render. Scene(vertices, faces): an N x 3 array of positions
    and an M x 3 array of vertex indices (triangles of zero area are left out; hits name
    the faces' rows). gridrt.load(path) reads a file as the command line does."""

    def __init__(self, vertices, faces, device=""):
        self._core = _gridrt.scene_from_arrays(vertices, faces, _device_spec(device))

    @classmethod
    def _wrap(cls, core):
        scene = cls.__new__(cls)
        scene._core = core
        return scene

    @property
    def triangle_count(self):
        return self._core.triangle_count

    @property
    def warnings(self):
        """What the loader left out, as the command line would warn."""
        return list(self._core.warnings)

    def intersect(self, origins, directions, tmax=math.inf):
        """Closest hits of rays from origins (N x 3) along directions (N x 3, any non-zero
        length: t is in units of it) in (0, tmax] (a number or N values), through the
        GridRT intersector on the scene's device."""
        return Hits(self._core.intersect(origins, directions, tmax))

    def occluded(self, origins, directions, tmax=math.inf):
        """Per ray, whether any triangle lies in (0, tmax) (shadow rays): a bool array."""
        return self._core.occluded(origins, directions, tmax).view(_np.int32)[:, 1] >= 0

    def __repr__(self):
        return f"gridrt.Scene({self.triangle_count} triangles)"


def load(path, device=""):
    """The scene of a glTF (.gltf, .glb) or mesh file (OBJ, PLY, STL, ...), in its still
    pose, as the command line loads it."""
    return Scene._wrap(_gridrt.load(str(path), _device_spec(device)))


# The command line's options that write files or print instead of rendering.
_FILE_OPTIONS = ("output", "format", "force", "aov", "aov_file", "stats", "stats_json",
                 "frames", "list_devices", "help", "version")


def _device_spec(device):
    return str(device) if device is not None else ""


def _flag_arguments(options):
    """The command line's arguments for keyword options: max_depth=2 -> --max-depth 2,
    alpha=True -> --alpha (False: left out), background=(r, g, b) -> --background r,g,b,
    look_at=((ex, ey, ez), (tx, ty, tz)) -> --look-at ex,ey,ez:tx,ty,tz,
    crop=(x0, y0, x1, y1) -> --crop x0,y0,x1,y1."""
    arguments = []
    for name, value in options.items():
        if value is None:
            continue
        flag = "--" + name.replace("_", "-")
        if value is True:
            arguments.append(flag)
        elif value is False:
            continue
        else:
            arguments += [flag, _option_text(name, value)]
    return arguments


def _option_text(name, value):
    if isinstance(value, str):
        return value
    if name == "look_at" and len(value) == 2:
        return ":".join(",".join(repr(float(x)) for x in point) for point in value)
    if isinstance(value, (tuple, list, _np.ndarray)):
        return ",".join(str(x) if isinstance(x, (int, _np.integer)) else repr(float(x))
                        for x in value)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def render(scene=None, width=None, height=None, **options):
    """The image the command line renders for the same options: an H x W x 3 float32
    array of linear RGB (x 4 with alpha=True: premultiplied, as its .exr holds it). scene:
    a path, a Scene, or None for the built-in default scene. Options are named as the flags
    (max_depth=2 for --max-depth 2; device=, threads=, spp=, accel=, ...)."""
    for name in _FILE_OPTIONS:
        if name in options:
            raise ValueError(f"{name}: render() returns the image; the gridrt command writes "
                             "files")
    arguments = _flag_arguments(dict(width=width, height=height, **options))
    core = None
    if isinstance(scene, Scene):
        core = scene._core
        if options.get("device") is None and core.device:
            arguments += ["--device", core.device]
    elif scene is not None:
        arguments += ["--", str(scene)]  # a path is never taken for a flag
    pixels, notes = _gridrt.render(arguments, core)
    for note in notes:
        _warnings.warn("gridrt: " + note, stacklevel=2)
    return pixels
