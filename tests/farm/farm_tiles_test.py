"""A 4x4-tile frame rendered on two loopback workers is the single gridrt render, file for
file (EXR and PNG); with the tiles handed out nearest the centre first as well; a .gltf
whose buffer is a file beside it reaches the workers with that file; and --shared-scene
renders from the path itself, sending nothing."""
import base64
import json
import os
import sys
import tempfile
import unittest

from farm_support import GRIDRT, SIZE, SOURCE, LoopbackCluster, farm, image_bytes, run

sys.path.insert(0, os.path.join(SOURCE, "tools"))
from gridrt_farm.scene_bundle import SceneBundle  # noqa: E402
from gridrt_farm.worker_task import SCENE_CACHE  # noqa: E402


class FarmTiles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # The workers' temporary folder, where they keep the scenes they are sent.
        cls.worker_tmp = tempfile.mkdtemp(prefix="farm-workers-tmp-")
        cls.cluster = LoopbackCluster(workers=2, env={"TMPDIR": cls.worker_tmp})

    @classmethod
    def tearDownClass(cls):
        cls.cluster.close()

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-tiles-")

    def expect_farm_equals_single(self, name, extra, farm_extra=(), tiles="4x4"):
        single = os.path.join(self.folder, "single_" + name)
        farmed = os.path.join(self.folder, "farm_" + name)
        r = run([GRIDRT, *SIZE, *extra, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run(farm(self.cluster, "--tiles", tiles, *farm_extra, *SIZE, *extra, "-o", farmed))
        self.assertEqual(r.returncode, 0, r.stderr)
        nx, ny = map(int, tiles.split("x"))
        self.assertIn(f"{nx * ny} tasks", r.stderr)
        self.assertEqual(image_bytes(farmed), image_bytes(single),
                         f"the farm's {name} differs from gridrt's")
        # Nothing is left beside the output but the two images (and a scene made here).
        left = {n for n in os.listdir(self.folder) if not n.startswith("scene")}
        self.assertEqual(left, {os.path.basename(single), os.path.basename(farmed)})

    def test_exr_frame_is_the_single_render(self):
        self.expect_farm_equals_single("frame.exr", ["--spp", "2"])

    def test_png_frame_is_the_single_render(self):
        self.expect_farm_equals_single("frame.png", ["--spp", "2"])

    def test_adaptive_aa_tiles_nearest_the_centre_first(self):
        self.expect_farm_equals_single("adaptive.png", ["--aa", "adaptive", "--aa-samples", "3"],
                                       ["--tile-order", "centre"])

    def gltf_with_its_buffer_in_a_file(self, label):
        """The default scene as a .gltf whose buffer is 'scene data.bin' beside it; `label`
        makes its bytes (and so the digest it is kept under) its own."""
        with open(os.path.join(SOURCE, "scenes", "default.gltf")) as f:
            document = json.load(f)
        (buffer,) = document["buffers"]
        data = base64.b64decode(buffer["uri"].split(",", 1)[1])
        with open(os.path.join(self.folder, "scene data.bin"), "wb") as f:
            f.write(data)
        buffer["uri"] = "scene%20data.bin"  # a URI: the space percent-encoded
        document["extras"] = {"test": label}
        scene = os.path.join(self.folder, "scene.gltf")
        with open(scene, "w") as f:
            json.dump(document, f)
        return scene

    def kept_on_workers(self, scene):
        return os.path.isdir(os.path.join(self.worker_tmp, SCENE_CACHE,
                                          SceneBundle(scene).digest))

    def test_a_gltf_whose_buffer_is_a_file_reaches_the_workers_with_it(self):
        scene = self.gltf_with_its_buffer_in_a_file("sent")
        self.expect_farm_equals_single("external.png", [scene], tiles="2x2")
        self.assertTrue(self.kept_on_workers(scene))

    def test_a_shared_scene_is_read_from_its_path_and_not_sent(self):
        scene = self.gltf_with_its_buffer_in_a_file("shared")
        self.expect_farm_equals_single("shared.png", [scene], ["--shared-scene"], tiles="2x2")
        self.assertFalse(self.kept_on_workers(scene))


if __name__ == "__main__":
    unittest.main()
