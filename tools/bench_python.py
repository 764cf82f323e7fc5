#!/usr/bin/env python3
"""Rays a second from Python: gridrt.Scene.intersect against the gridrt program's own
primary-ray frame and against Embree 4 through embreex (where it is installed), on the
same scene and camera. Each figure is the median of --rounds rounds after a warm-up.

    PYTHONPATH=build/python python3 tools/bench_python.py   # bench/results/python.csv
    tools/bench_python.py --width 640 --height 480 --rounds 5 --scene scenes/models/teapot.glb

The Python rays are the camera's pixel centres through the glTF camera of the scene (or
a camera looking at the box from +Z), one ray a pixel, given to intersect as numpy arrays
(closest hit, any order): the intersector's general path, traversal lists on the host. The
program's frame is its --primary-only frame, whose primary rays take the camera bundles
(docs/architecture.md), with the primary rays counted from its --stats-json.
"""
import argparse
import csv
import math
import os
import statistics
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "python"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import gridrt  # noqa: E402
from glb_mesh import read_document, read_triangles  # noqa: E402
from bench_runner import gridrt_stats  # noqa: E402

RESULTS = os.path.join(ROOT, "bench", "results", "python.csv")


def quaternion_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def camera_of(path):
    """(eye, rotation 3x3, vertical fov) of the .glb's first camera node, else None."""
    document, _ = read_document(path)
    for node in document.get("nodes", []):
        if "camera" in node:
            camera = document["cameras"][node["camera"]]
            rotation = quaternion_matrix(node.get("rotation", [0, 0, 0, 1]))
            return (np.array(node.get("translation", [0, 0, 0]), float), rotation,
                    camera["perspective"]["yfov"])
    return None


def pinhole_rays(path, width, height):
    eye, rotation, yfov = camera_of(path)
    half = math.tan(yfov / 2)
    xs = ((np.arange(width) + 0.5) / width * 2 - 1) * half * width / height
    ys = (1 - (np.arange(height) + 0.5) / height * 2) * half
    gx, gy = np.meshgrid(xs, ys)
    local = np.stack([gx, gy, -np.ones_like(gx)], axis=-1).reshape(-1, 3)
    directions = local @ rotation.T
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    origins = np.broadcast_to(eye, directions.shape)
    return np.ascontiguousarray(origins, np.float32), np.ascontiguousarray(directions, np.float32)


def timed(call, rounds):
    call()  # warm-up: kernels, buffers
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def command_line_mrays(scene, width, height, rounds):
    s = gridrt_stats([scene, "--primary-only", "--width", str(width), "--height", str(height)],
                     rounds)
    return s["rays"]["primary"] / (s["frame_ms"] * 1e3), s["frame_ms"]


def embree_scene(vertices, faces):
    try:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh
    except ImportError:
        return None
    scene = rtcore_scene.EmbreeScene()
    TriangleMesh(scene, vertices[faces].astype(np.float32))
    return scene


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes", "models", "bunny.glb"))
    p.add_argument("--width", type=int, default=1280)
    p.add_argument("--height", type=int, default=960)
    p.add_argument("--rounds", type=int, default=9)
    p.add_argument("--out", default=RESULTS)
    a = p.parse_args()

    origins, directions = pinhole_rays(a.scene, a.width, a.height)
    rays = len(origins)
    scene = gridrt.load(a.scene)
    rows = []
    seconds = timed(lambda: scene.intersect(origins, directions), a.rounds)
    hits = scene.intersect(origins, directions)
    rows.append(("gridrt.Scene.intersect (Python, numpy rays)", rays / seconds / 1e6,
                 seconds * 1e3, int((hits.prim >= 0).sum())))
    mrays, frame_ms = command_line_mrays(a.scene, a.width, a.height, a.rounds)
    rows.append(("gridrt --primary-only (the program's frame)", mrays, frame_ms, ""))

    try:
        vertices, faces = read_triangles(a.scene)
    except ValueError:
        vertices = faces = None
    embree = embree_scene(vertices, faces) if vertices is not None else None
    if embree is not None:
        seconds = timed(lambda: embree.run(origins, directions, output=1), a.rounds)
        result = embree.run(origins, directions, output=1)
        prim = np.asarray(result["primID"])
        same = int(((prim >= 0) == (hits.prim >= 0)).sum())
        rows.append(("embreex 4 (Python, numpy rays)", rays / seconds / 1e6, seconds * 1e3,
                     int((prim >= 0).sum())))
        print(f"gridrt and embreex agree on hit or miss for {same} of {rays} rays, on the "
              f"triangle for {int((prim == hits.prim).sum())}")
    else:
        rows.append(("embreex 4", float("nan"), float("nan"), "not installed"))

    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["what", "mrays_per_s", "ms", "hits", "rays", "scene", "width", "height",
                    "device"])
        device = gridrt.devices()[0]["name"] if gridrt.devices() else ""
        for row in rows:
            w.writerow(list(row) + [rays, os.path.basename(a.scene), a.width, a.height, device])
    print(f"{'':48} {'Mrays/s':>9} {'ms':>9}")
    for what, mr, ms, _ in rows:
        print(f"{what:48} {mr:9.2f} {ms:9.2f}")
    print(f"written {a.out}")


if __name__ == "__main__":
    main()
