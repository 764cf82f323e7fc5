"""Sequences on two loopback workers: an 8-frame job (gridrt --frames K:K per task) is the
8 single renders, file for file, and --resume renders only the frames that are missing.
They run against tests/farm/anim_stand_in.py, which gives gridrt's animation interface
(--frames, --fps, a printf -o) eight different cameras; the first test also runs against
gridrt itself once gridrt has --frames."""
import os
import tempfile
import unittest

from farm_support import (GRIDRT, SIZE, STAND_IN, LoopbackCluster, farm, image_bytes,
                          gridrt_has_frames, run)

FRAMES = 8


class FarmFrames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # The stand-in runs on the workers: they are told where it logs when they start.
        cls.log = os.path.join(tempfile.mkdtemp(prefix="farm-frames-log-"), "frames.log")
        cls.cluster = LoopbackCluster(workers=2, env={"FARM_STAND_IN_LOG": cls.log})

    @classmethod
    def tearDownClass(cls):
        cls.cluster.close()

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-frames-")
        if os.path.exists(self.log):
            os.remove(self.log)

    def references(self, gridrt, frames, pattern):
        for k in frames:
            r = run([gridrt, *SIZE, "--frames", f"{k}:{k}", "--fps", "24", "-q", "-o", pattern])
            self.assertEqual(r.returncode, 0, r.stderr)

    def expect_sequence(self, gridrt, tiles):
        ref = os.path.join(self.folder, "ref_%04d.png")
        out = os.path.join(self.folder, "out_%04d.png")
        self.references(gridrt, range(FRAMES), ref)
        r = run(farm(self.cluster, "--frames", f"0:{FRAMES - 1}", "--tiles", tiles, *SIZE,
                     "--fps", "24", "-o", out, gridrt=gridrt))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(f"{FRAMES} frame(s) written", r.stderr)
        images = [image_bytes(out % k) for k in range(FRAMES)]
        for k in range(FRAMES):
            self.assertEqual(images[k], image_bytes(ref % k), f"frame {k}")
        self.assertEqual(len(set(images)), FRAMES, "the frames should all differ")

    def test_eight_frames_are_eight_single_renders(self):
        self.expect_sequence(STAND_IN, "1x1")

    def test_eight_tiled_frames_are_eight_single_renders(self):
        self.expect_sequence(STAND_IN, "2x2")

    def test_eight_frames_of_gridrts_own_animation(self):
        if not gridrt_has_frames():
            self.skipTest("gridrt has no --frames yet")
        self.expect_sequence(GRIDRT, "2x1")

    def test_resume_renders_only_the_missing_frames(self):
        out = os.path.join(self.folder, "seq_%04d.exr")
        job = farm(self.cluster, "--frames", "0:3", *SIZE, "-o", out, gridrt=STAND_IN)
        r = run(job)
        self.assertEqual(r.returncode, 0, r.stderr)
        first = {k: image_bytes(out % k) for k in range(4)}
        kept = {k: os.stat(out % k).st_ino for k in (0, 2)}
        os.remove(out % 1)
        os.remove(out % 3)
        os.remove(self.log)  # the first run's frames
        r = run(job + ["--resume"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("2 frame(s) written, 2 kept", r.stderr)
        with open(self.log) as f:
            self.assertEqual(sorted(int(line) for line in f), [1, 3])
        for k in range(4):
            self.assertEqual(image_bytes(out % k), first[k], f"frame {k}")
        for k, inode in kept.items():
            self.assertEqual(os.stat(out % k).st_ino, inode, f"frame {k} was written again")


if __name__ == "__main__":
    unittest.main()
