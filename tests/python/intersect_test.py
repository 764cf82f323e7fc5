"""Scene.intersect and Scene.occluded against a double-precision ray-triangle test in numpy
(ray_triangle_oracle.py) on thousands of random rays against the bunny, its triangles
read from the .glb by numpy (glb_mesh.py): misses, hits, triangle ids, t, u, v."""
import os
import tempfile
import threading
import time
import unittest

import numpy as np

import gridrt
from glb_mesh import read_triangles
from python_support import DeviceTestCase, model
from ray_triangle_oracle import closest_hits, hit_of_triangle

MESH = "bunny_res3.glb"  # 3,851 triangles: the oracle tests every one against every ray
RAY_COUNT = 3000
# gridrt's float32 t against the double-precision t: float32's rounding of the vertices,
# the edges and the Moeller-Trumbore products, far below this share of t.
T_RELATIVE_TOLERANCE = 1e-4
# The same for the barycentrics u, v (of order 1): float32 rounding of their products,
# divided by the determinant, which grazing rays make small (6e-5 seen on these rays).
BARYCENTRIC_TOLERANCE = 5e-4
# A ray this close to a triangle's edge (in barycentrics) may be found by float32 on
# either side of it: hit or miss, or the neighbour's hit at the same t.
EDGE_TOLERANCE = 1e-4
# Of the rays, at most this share may be such edge cases (1 in 3,000 is).
MAX_EDGE_CASE_SHARE = 0.005
# Rays of the query that Python's lock must not wait for: enough for a query of about a
# second on two cores, far longer than the pauses another thread sees while it runs.
LONG_QUERY_RAYS = 1 << 20
# The longest pause Python's other thread may see while the query runs, as a share of the
# query's time: with the lock held throughout it would be the whole query.
MAX_PAUSE_SHARE = 0.5


def random_rays(vertices, count, seed):
    """Rays from a sphere around the mesh towards points in its box (most hit), in random
    directions (most miss), and from inside the box; directions of random length;
    a quarter with a finite tmax."""
    rng = np.random.default_rng(seed)
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    around = rng.normal(size=(count, 3))
    around = centre + 2.5 * radius * around / np.linalg.norm(around, axis=1, keepdims=True)
    inside = lo + rng.random((count, 3)) * (hi - lo)
    towards = lo + rng.random((count, 3)) * (hi - lo)
    kind = rng.integers(0, 3, count)  # 0: towards the box, 1: anywhere, 2: from inside
    origins = np.where((kind == 2)[:, None], inside, around)
    directions = np.where((kind == 0)[:, None], towards - around, rng.normal(size=(count, 3)))
    directions *= rng.uniform(0.25, 4.0, (count, 1))
    tmax = np.where(rng.random(count) < 0.25, rng.uniform(0.0, 3.0, count) * radius /
                    np.linalg.norm(directions, axis=1), np.inf)
    return origins.astype(np.float32), directions.astype(np.float32), tmax.astype(np.float32)


class IntersectAgainstOracle(DeviceTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.vertices, cls.faces = read_triangles(model(MESH))
        cls.origins, cls.directions, cls.tmax = random_rays(cls.vertices, RAY_COUNT, seed=56)
        # The oracle sees the rays gridrt sees: the float32 values, in double.
        cls.expected = closest_hits(cls.vertices, cls.faces, cls.origins, cls.directions,
                                    cls.tmax)

    def check_against_oracle(self, hits, faces_of_prim):
        """hits: gridrt's; faces_of_prim maps its prim to the oracle's face rows."""
        t, prim, u, v = self.expected
        got_prim = np.where(hits.prim >= 0, faces_of_prim(hits.prim), -1)
        self.assertGreater((prim >= 0).sum(), RAY_COUNT // 4, "too few hits to test")
        self.assertGreater((prim < 0).sum(), RAY_COUNT // 10, "too few misses to test")
        agree = got_prim == prim
        both = agree & (prim >= 0)
        np.testing.assert_array_less(np.abs(hits.t[both] - t[both]),
                                     T_RELATIVE_TOLERANCE * t[both] + 1e-30)
        np.testing.assert_array_less(np.abs(hits.u[both] - u[both]), BARYCENTRIC_TOLERANCE)
        np.testing.assert_array_less(np.abs(hits.v[both] - v[both]), BARYCENTRIC_TOLERANCE)
        self.assertTrue(np.all(np.isinf(hits.t[agree & (prim < 0)])), "a miss's t is inf")
        # Where they disagree, each answer must be an edge case: the oracle's hit near its
        # triangle's edge, gridrt's hit on its triangle within the edge tolerance at the
        # oracle's t (or nearer than the oracle's where the oracle missed).
        bad = np.flatnonzero(~agree)
        edge_cases = 0
        for i in bad:
            oracle_on_edge = prim[i] >= 0 and min(u[i], v[i], 1 - u[i] - v[i]) < EDGE_TOLERANCE
            gridrt_on_edge = False
            if got_prim[i] >= 0:
                tt, uu, vv = hit_of_triangle(self.vertices, self.faces, got_prim[i:i + 1],
                                             self.origins[i:i + 1], self.directions[i:i + 1])
                near_edge = min(uu[0], vv[0], 1 - uu[0] - vv[0]) > -EDGE_TOLERANCE
                same_t = abs(tt[0] - hits.t[i]) <= T_RELATIVE_TOLERANCE * hits.t[i]
                not_farther = prim[i] < 0 or hits.t[i] <= t[i] * (1 + T_RELATIVE_TOLERANCE)
                gridrt_on_edge = near_edge and same_t and not_farther
            self.assertTrue(oracle_on_edge or gridrt_on_edge,
                            f"ray {i}: gridrt prim {got_prim[i]} t {hits.t[i]}, double-precision "
                            f"prim {prim[i]} t {t[i]} (u {u[i]}, v {v[i]})")
            edge_cases += 1
        self.assertLessEqual(edge_cases, MAX_EDGE_CASE_SHARE * RAY_COUNT)

    def test_scene_of_arrays_agrees_with_double_precision(self):
        # A zero-area face first: gridrt leaves it out, and hits still name the rows.
        faces = np.vstack([[0, 0, 1], self.faces])
        scene = gridrt.Scene(self.vertices, faces)
        self.assertEqual(scene.triangle_count, len(self.faces))
        hits = scene.intersect(self.origins, self.directions, self.tmax)
        self.check_against_oracle(hits, lambda p: p - 1)

    def test_loaded_file_agrees_with_double_precision(self):
        # prim is the global triangle id of the primid AOV: the file's index order.
        scene = gridrt.load(model(MESH))
        hits = scene.intersect(self.origins, self.directions, self.tmax)
        self.check_against_oracle(hits, lambda p: p)

    def test_occluded_is_whether_any_hit_lies_before_tmax(self):
        scene = gridrt.Scene(self.vertices, self.faces)
        blocked = scene.occluded(self.origins, self.directions, self.tmax)
        _, prim, u, v = self.expected
        hit = prim >= 0
        on_edge = hit & (np.minimum(np.minimum(u, v), 1 - u - v) < EDGE_TOLERANCE)
        differ = (blocked != hit) & ~on_edge
        self.assertEqual(differ.sum(), 0, f"rays {np.flatnonzero(differ)[:10]}")
        self.assertEqual(blocked.dtype, np.bool_)


class IntersectInput(DeviceTestCase):
    """How the arrays reach the intersector, without the oracle."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.vertices, cls.faces = read_triangles(model(MESH))
        cls.origins, cls.directions, cls.tmax = random_rays(cls.vertices, RAY_COUNT, seed=7)

    def test_float64_and_strided_input_is_converted_to_the_same_hits(self):
        scene = gridrt.Scene(self.vertices, self.faces)
        first = scene.intersect(self.origins, self.directions, self.tmax)
        # Every other column of a wider float64 array: neither float32 nor contiguous.
        wide = np.zeros((RAY_COUNT, 6))
        wide[:, ::2] = self.origins
        strided = wide[:, ::2]
        self.assertFalse(strided.flags.c_contiguous)
        again = scene.intersect(strided, self.directions.astype(np.float64),
                                self.tmax.astype(np.float64))
        np.testing.assert_array_equal(first.records, again.records)

    def test_other_threads_run_while_the_device_works(self):
        scene = gridrt.Scene(self.vertices, self.faces)
        origins, directions, _ = random_rays(self.vertices, LONG_QUERY_RAYS, seed=11)
        scene.intersect(origins[:16], directions[:16])  # the grid and kernels, beforehand
        span = {}

        def query():
            span["start"] = time.perf_counter()
            scene.intersect(origins, directions)
            span["end"] = time.perf_counter()

        worker = threading.Thread(target=query)
        ticks = []
        worker.start()
        while worker.is_alive():
            ticks.append(time.perf_counter())
        worker.join()
        during = [t for t in ticks if span["start"] <= t <= span["end"]]
        length = span["end"] - span["start"]
        self.assertGreater(len(during), 1, "this thread never ran while the query did")
        pauses = np.diff([span["start"]] + during + [span["end"]])
        self.assertLess(pauses.max(), MAX_PAUSE_SHARE * length,
                        f"a pause of {pauses.max():.3f} s in a query of {length:.3f} s")

    def test_a_mesh_file_gives_the_hits_of_its_arrays(self):
        # An OBJ (read through assimp, as the command line reads it) of the same triangles.
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "bunny.obj")
            with open(path, "w") as obj:
                for x, y, z in self.vertices.astype(np.float32):
                    obj.write(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n")
                for a, b, c in self.faces + 1:
                    obj.write(f"f {a} {b} {c}\n")
            from_file = gridrt.load(path).intersect(self.origins, self.directions, self.tmax)
        from_arrays = gridrt.Scene(self.vertices, self.faces).intersect(
            self.origins, self.directions, self.tmax)
        self.assertGreater((from_arrays.prim >= 0).sum(), RAY_COUNT // 5)
        for name in ("t", "prim", "u", "v"):
            np.testing.assert_array_equal(getattr(from_file, name), getattr(from_arrays, name))

    def test_views_share_one_buffer(self):
        scene = gridrt.Scene(self.vertices, self.faces)
        hits = scene.intersect(self.origins[:10], self.directions[:10])
        for column in (hits.t, hits.prim, hits.u, hits.v):
            self.assertTrue(np.shares_memory(column, hits.records))
            self.assertEqual(len(column), 10)


if __name__ == "__main__":
    unittest.main()
