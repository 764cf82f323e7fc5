"""The farm's pieces without a cluster: its command line (gridrt's options told apart from
the scene, refused options, output patterns), tiles, the tile order, the image size a
scene's camera gives, and the local cluster it starts without --scheduler."""
import json
import os
import struct
import sys
import tempfile
import time
import unittest

from farm_support import (FARM, GRIDRT, MERGE_TILES, SIZE, SOURCE, file_bytes,
                          image_bytes, run)

sys.path.insert(0, os.path.join(SOURCE, "tools"))
from gridrt_farm.command_line import FarmCommand, UsageError  # noqa: E402
from gridrt_farm.main import image_size  # noqa: E402
from gridrt_farm.scene_bundle import SceneBundle, camera_widths, gltf_json  # noqa: E402
from gridrt_farm.tiles import ordered, split  # noqa: E402


class FarmCommandLine(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-cli-")
        self.out = os.path.join(self.folder, "out.png")

    def test_the_scene_is_told_apart_from_option_values(self):
        c = FarmCommand(["--spp", "4", "scene.glb", "--primary-only", "--width=64", "-q",
                         "--background", "0.1,0.2,0.3", "-o", self.out])
        self.assertEqual(c.scene, "scene.glb")
        self.assertEqual(c.gridrt_options, [("--spp", "4"), ("--primary-only", None),
                                            ("--background", "0.1,0.2,0.3")])
        self.assertEqual((c.width, c.height, c.quiet), (64, None, True))
        self.assertIsNone(FarmCommand(["--spp", "4", "-o", self.out]).scene)

    def test_options_the_farm_sets_itself_are_refused_in_one_line(self):
        for flag, value in [("--crop", "0,0,8,8"), ("--aov", "depth=d.exr"),
                            ("--stats-json", "s.json"), ("--repeat", "3")]:
            r = run([FARM, flag, value, "-o", self.out])
            self.assertEqual(r.returncode, 2, flag)
            self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
            self.assertIn(flag, r.stderr)
        self.assertEqual(os.listdir(self.folder), [])

    def test_bad_farm_values_are_usage_errors(self):
        for args in (["--tiles", "4"], ["--tiles", "0x4"], ["--frames", "5:2"],
                     ["--frames", "0:3"],  # -o without a frame number
                     ["--tiles", "65x2"],  # more columns than the 64 pixels
                     ["-o", os.path.join(self.folder, "x.bmp")],
                     ["-o", "/no/such/folder/x.png"]):
            argv = [FARM, *SIZE, *args] + ([] if "-o" in args else ["-o", self.out])
            r = run(argv)
            self.assertEqual(r.returncode, 2, f"{args}: {r.stderr}")
            self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
            self.assertTrue(r.stderr.startswith("gridrt-farm: "), r.stderr)

    def test_a_missing_scene_is_one_line_and_exit_1(self):
        r = run([FARM, os.path.join(self.folder, "nowhere.glb"), "-o", self.out])
        self.assertEqual(r.returncode, 1)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("nowhere.glb", r.stderr)

    def test_frame_patterns_expand_the_frame_number_once(self):
        c = FarmCommand(["--frames", "2:4", "-o", os.path.join(self.folder, "a%%_%03d.exr")])
        self.assertEqual(c.frame_numbers(), [2, 3, 4])
        self.assertEqual(c.output_of(3), os.path.join(self.folder, "a%_003.exr"))
        self.assertEqual(c.tiles, (1, 1))
        self.assertEqual(FarmCommand(["-o", self.out]).tiles, (4, 4))

    def test_tiles_cover_every_pixel_once(self):
        for w, h, nx, ny in [(64, 48, 4, 4), (67, 13, 5, 3), (7, 5, 7, 5), (640, 480, 1, 1)]:
            covered = {}
            for t in split(w, h, nx, ny):
                for y in range(t.y0, t.y1):
                    for x in range(t.x0, t.x1):
                        covered[(x, y)] = covered.get((x, y), 0) + 1
            self.assertEqual(len(covered), w * h)
            self.assertEqual(set(covered.values()), {1})
        with self.assertRaises(ValueError):
            split(4, 4, 5, 1)

    def test_centre_order_starts_at_the_centre_and_keeps_every_tile(self):
        tiles = split(64, 48, 5, 5)
        centre = ordered(tiles, 64, 48, "centre")
        self.assertEqual(sorted(centre, key=tiles.index), tiles)
        first = centre[0]
        self.assertTrue(first.x0 <= 32 < first.x1 and first.y0 <= 24 < first.y1, first)
        corners = {tiles[0], tiles[4], tiles[20], tiles[24]}
        self.assertEqual(set(centre[-4:]), corners)
        self.assertEqual(ordered(tiles, 64, 48, "raster"), tiles)

    def test_a_cameras_aspect_sizes_the_image_as_gridrt_does(self):
        doc = {"cameras": [{"type": "perspective",
                            "perspective": {"aspectRatio": 1.5, "yfov": 0.8, "znear": 0.1}}]}
        self.assertEqual(camera_widths(doc), {720})
        no_size = FarmCommand(["-o", self.out])
        self.assertEqual(image_size(no_size, doc), (720, 480))
        self.assertEqual(image_size(FarmCommand(["--height", "100", "-o", self.out]), doc),
                         (640, 100))
        two = {"cameras": doc["cameras"] + [{"perspective": {"aspectRatio": 2.0}}]}
        with self.assertRaises(UsageError):
            image_size(no_size, two)
        self.assertEqual(image_size(no_size, None), (640, 480))

    def test_a_glb_scenes_json_and_files_are_read(self):
        text = json.dumps({"asset": {"version": "2.0"},
                           "buffers": [{"uri": "mesh%20data.bin", "byteLength": 4}]}).encode()
        text += b" " * (-len(text) % 4)
        glb = b"glTF" + struct.pack("<II", 2, 20 + len(text)) + \
            struct.pack("<II", len(text), 0x4E4F534A) + text
        path = os.path.join(self.folder, "s.glb")
        with open(path, "wb") as f:
            f.write(glb)
        with open(os.path.join(self.folder, "mesh data.bin"), "wb") as f:
            f.write(b"1234")
        self.assertEqual(gltf_json(glb)["asset"]["version"], "2.0")
        bundle = SceneBundle(path)
        self.assertEqual(sorted(bundle.files), ["mesh data.bin", "s.glb"])
        self.assertEqual(bundle.files["mesh data.bin"], b"1234")

    def test_exr_comparison_ignores_the_capture_date_alone(self):
        a, b, c = (os.path.join(self.folder, n) for n in ("a.exr", "b.exr", "c.exr"))
        for path, extra in ((a, []), (b, []), (c, ["--ambient", "0.06"])):
            r = run([GRIDRT, *SIZE, *extra, "-q", "-o", path])
            self.assertEqual(r.returncode, 0, r.stderr)
            time.sleep(1.0)  # capDate counts seconds: a and b are written at different ones
        self.assertNotEqual(file_bytes(a), file_bytes(b))
        self.assertEqual(image_bytes(a), image_bytes(b))
        self.assertNotEqual(image_bytes(a), image_bytes(c))
        self.assertEqual(len(image_bytes(a)), len(file_bytes(a)) - len(b"capDate\0string\0") - 4
                         - len("2026:12:02 02:03:48"))

    def test_without_a_scheduler_a_local_cluster_renders_the_frame(self):
        single, farmed = os.path.join(self.folder, "single.png"), self.out
        r = run([GRIDRT, *SIZE, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run([FARM, "--workers", "2", "--gridrt", GRIDRT, "--merge-tiles", MERGE_TILES,
                 "--tiles", "2x2", *SIZE, "-o", farmed])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("4 tasks", r.stderr)
        self.assertEqual(image_bytes(farmed), image_bytes(single))


if __name__ == "__main__":
    unittest.main()
