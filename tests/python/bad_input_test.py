"""Bad arrays and options raise ValueError with gridrt's one-line message; errors that
are no fault of the arguments' shape or values raise RuntimeError."""
import math
import os
import tempfile
import unittest

import numpy as np

import gridrt
from python_support import DeviceTestCase

TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
FACE = np.array([[0, 1, 2]])


class BadInput(DeviceTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.scene = gridrt.Scene(TRIANGLE, FACE)
        cls.origins = np.array([[0.2, 0.2, 1.0], [5.0, 5.0, 1.0]], np.float32)
        cls.directions = np.array([[0, 0, -1], [0, 0, -1]], np.float32)

    def assert_value_error(self, pattern, call, *args, **kwargs):
        with self.assertRaisesRegex(ValueError, pattern) as caught:
            call(*args, **kwargs)
        self.assertNotIn("\n", str(caught.exception))

    def test_a_valid_query_hits_and_misses(self):
        hits = self.scene.intersect(self.origins, self.directions)
        self.assertEqual(list(hits.prim), [0, -1])
        self.assertAlmostEqual(float(hits.t[0]), 1.0, places=6)
        self.assertTrue(math.isinf(hits.t[1]))

    def test_wrong_shapes(self):
        self.assert_value_error(r"origins: expected shape \(N, 3\), got \(2, 2\)",
                                self.scene.intersect, self.origins[:, :2], self.directions)
        self.assert_value_error(r"directions: expected shape \(2, 3\), got \(1, 3\)",
                                self.scene.intersect, self.origins, self.directions[:1])
        self.assert_value_error(r"origins: expected shape \(N, 3\), got \(6,\)",
                                self.scene.intersect, self.origins.ravel(), self.directions)
        self.assert_value_error(r"tmax: expected a number or shape \(2,\)",
                                self.scene.intersect, self.origins, self.directions, [1, 2, 3])
        self.assert_value_error(r"vertices: expected shape \(N, 3\)", gridrt.Scene,
                                TRIANGLE[:, :2], FACE)
        self.assert_value_error(r"faces: expected shape \(M, 3\)", gridrt.Scene, TRIANGLE,
                                FACE.ravel())

    def test_nan_and_infinite_values(self):
        for bad in (np.nan, np.inf):
            origins = self.origins.copy()
            origins[1, 2] = bad
            self.assert_value_error("origins: row 1 holds a NaN or infinite value",
                                    self.scene.intersect, origins, self.directions)
            directions = self.directions.copy()
            directions[0, 0] = bad
            self.assert_value_error("directions: row 0 holds a NaN or infinite value",
                                    self.scene.intersect, self.origins, directions)
            vertices = TRIANGLE.copy()
            vertices[2, 1] = bad
            self.assert_value_error("vertices: row 2 holds a NaN or infinite coordinate",
                                    gridrt.Scene, vertices, FACE)
        self.assert_value_error("tmax: is nan", self.scene.intersect, self.origins,
                                self.directions, math.nan)

    def test_bad_values(self):
        self.assert_value_error("directions: row 1 is zero", self.scene.intersect,
                                self.origins, np.array([[0, 0, -1], [0, 0, 0]]))
        self.assert_value_error("tmax: row 0 is -1", self.scene.intersect, self.origins,
                                self.directions, np.array([-1.0, 1.0]))
        self.assert_value_error("faces: row 0 names vertex 3, outside 0..2", gridrt.Scene,
                                TRIANGLE, [[0, 1, 3]])
        self.assert_value_error("faces: expected an array of integers", gridrt.Scene, TRIANGLE,
                                FACE.astype(np.float32))
        self.assert_value_error("faces: no triangle of non-zero area", gridrt.Scene, TRIANGLE,
                                [[0, 1, 1]])
        self.assert_value_error("origins: expected an array of numbers", self.scene.intersect,
                                [["a", "b", "c"]], self.directions[:1])

    def test_bad_options_carry_the_command_lines_message(self):
        self.assert_value_error("--max-depth: .*0..64", gridrt.render, None, width=8, height=8,
                                max_depth=-1)
        self.assert_value_error("no_such_option|no-such-option", gridrt.render, None,
                                no_such_option=3)
        self.assert_value_error("output: render\\(\\) returns the image", gridrt.render, None,
                                output="x.png")
        self.assert_value_error("unknown device|no device|device", gridrt.render, None,
                                device="no such device name")

    def test_an_image_too_large_for_the_machine_is_refused_before_it_is_made(self):
        with self.assertRaisesRegex(RuntimeError, "image 65536x65536 at 64 spp needs about"):
            gridrt.render(None, width=65536, height=65536, spp=64)

    def test_other_errors_are_runtime_errors(self):
        with tempfile.TemporaryDirectory() as folder:
            missing = os.path.join(folder, "missing.glb")
            with self.assertRaises(RuntimeError) as caught:
                gridrt.load(missing)
            self.assertIn("missing.glb", str(caught.exception))
            broken = os.path.join(folder, "broken.glb")
            with open(broken, "wb") as f:
                f.write(b"glTF not really")
            with self.assertRaises(RuntimeError):
                gridrt.load(broken)


if __name__ == "__main__":
    unittest.main()
