"""A 4x4-tile frame rendered on two loopback workers is the single gridrt render, file for
file (EXR and PNG); with the tiles handed out nearest the centre first as well."""
import os
import tempfile
import unittest

from farm_support import GRIDRT, SIZE, LoopbackCluster, farm, image_bytes, run


class FarmTiles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cluster = LoopbackCluster(workers=2)

    @classmethod
    def tearDownClass(cls):
        cls.cluster.close()

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-tiles-")

    def expect_farm_equals_single(self, name, extra, farm_extra=()):
        single = os.path.join(self.folder, "single_" + name)
        farmed = os.path.join(self.folder, "farm_" + name)
        r = run([GRIDRT, *SIZE, *extra, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run(farm(self.cluster, "--tiles", "4x4", *farm_extra, *SIZE, *extra, "-o", farmed))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("16 tasks", r.stderr)
        self.assertEqual(image_bytes(farmed), image_bytes(single),
                         f"the farm's {name} differs from gridrt's")
        # Nothing is left beside the output but the two images.
        self.assertEqual(sorted(os.listdir(self.folder)), sorted([os.path.basename(single),
                                                                  os.path.basename(farmed)]))

    def test_exr_frame_is_the_single_render(self):
        self.expect_farm_equals_single("frame.exr", ["--spp", "2"])

    def test_png_frame_is_the_single_render(self):
        self.expect_farm_equals_single("frame.png", ["--spp", "2"])

    def test_adaptive_aa_tiles_nearest_the_centre_first(self):
        self.expect_farm_equals_single("adaptive.png", ["--aa", "adaptive", "--aa-samples", "3"],
                                       ["--tile-order", "centre"])


if __name__ == "__main__":
    unittest.main()
