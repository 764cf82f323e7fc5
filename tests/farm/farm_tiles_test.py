"""A 4x4-tile frame rendered on two loopback workers is the single gridrt render, file for
file (EXR and PNG); with the tiles handed out nearest the centre first as well; a .gltf
whose buffer is a file beside it reaches the workers with that file; and --shared-scene
renders from the path itself, sending nothing. On a terminal the job shows its progress.
"""
import base64
import json
import os
import pty
import re
import subprocess
import sys
import tempfile
import unittest

from farm_support import (GRIDRT, RUN_SECONDS, SIZE, SOURCE, LoopbackCluster, farm,
                          image_bytes, run)

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

    def test_a_terminal_sees_the_progress_bar_and_a_pipe_only_the_summary(self):
        out = os.path.join(self.folder, "bar.png")
        main, terminal = pty.openpty()
        job = subprocess.Popen(farm(self.cluster, "--tiles", "4x4", *SIZE, "-o", out),
                               stdout=subprocess.DEVNULL, stderr=terminal)
        os.close(terminal)
        shown = b""
        while True:
            try:
                chunk = os.read(main, 4096)
            except OSError:  # the terminal's other end closed: the job is done
                break
            if not chunk:
                break
            shown += chunk
        os.close(main)
        self.assertEqual(job.wait(timeout=RUN_SECONDS), 0, shown)
        text = shown.decode()
        self.assertIn("[" + "#" * 24 + "] tasks 16/16, frames 1/1, 2 workers", text)
        self.assertRegex(text, r"tasks [0-9]+/16, frames 0/1, 2 workers, ")
        last = re.split(r"[\r\n]+", text.strip())[-1]  # the bar erased, then the summary
        self.assertTrue(last.startswith("\033[Kgridrt-farm: 1 frame(s) written, 16 tasks"), last)
        piped = run(farm(self.cluster, "--tiles", "2x2", *SIZE, "-o", out))
        self.assertEqual(piped.returncode, 0, piped.stderr)
        self.assertEqual(len(piped.stderr.splitlines()), 1, piped.stderr)
        self.assertNotIn("tasks 4/4", piped.stderr)


if __name__ == "__main__":
    unittest.main()
