"""Sequences on two loopback workers: an 8-frame job (gridrt --frames K:K per task) is the
8 single renders, file for file, and --resume renders only the frames that are missing.
They run against tests/farm/anim_stand_in.py, which gives gridrt's animation interface
(--frames, --fps, a printf -o) eight different cameras, and, where gridrt has --frames,
against gridrt itself on the default scene with its camera animated."""
import base64
import json
import os
import struct
import tempfile
import unittest

from farm_support import (GRIDRT, SIZE, SOURCE, STAND_IN, LoopbackCluster, farm,
                          image_bytes, run)

FRAMES = 8
FPS = 8  # the animated scene's eight frames span its one-second animation
CAMERA_PATH = [(-0.3, 1.0, 2.0), (0.3, 1.0, 2.0)]  # the camera's translation at 0 s and 1 s


def animated_default_scene(folder):
    """scenes/default.gltf with its camera node moving along CAMERA_PATH in one second
    (LINEAR), written to FOLDER/animated.gltf."""
    with open(os.path.join(SOURCE, "scenes", "default.gltf")) as f:
        doc = json.load(f)
    (buffer,) = doc["buffers"]
    data = bytearray(base64.b64decode(buffer["uri"].split(",", 1)[1]))
    data += b"\0" * (-len(data) % 4)
    times_at, data = len(data), data + struct.pack("<2f", 0.0, 1.0)
    path_at = len(data)
    data += struct.pack("<6f", *CAMERA_PATH[0], *CAMERA_PATH[1])
    buffer.update(uri="data:application/octet-stream;base64," + base64.b64encode(data).decode(),
                  byteLength=len(data))
    views, accessors = doc["bufferViews"], doc["accessors"]
    views += [{"buffer": 0, "byteOffset": times_at, "byteLength": 8},
              {"buffer": 0, "byteOffset": path_at, "byteLength": 24}]
    accessors += [{"bufferView": len(views) - 2, "componentType": 5126, "count": 2,
                   "type": "SCALAR", "min": [0.0], "max": [1.0]},
                  {"bufferView": len(views) - 1, "componentType": 5126, "count": 2,
                   "type": "VEC3"}]
    camera = next(k for k, n in enumerate(doc["nodes"]) if "camera" in n)
    matrix = doc["nodes"][camera].pop("matrix")  # an animated node takes TRS, not a matrix
    assert matrix == [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 2, 1], matrix  # a translation
    doc["nodes"][camera]["translation"] = [0.0, 1.0, 2.0]
    doc["animations"] = [{"name": "dolly", "samplers": [
        {"input": len(accessors) - 2, "output": len(accessors) - 1, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": camera, "path": "translation"}}]}]
    path = os.path.join(folder, "animated.gltf")
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


class FarmFrames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # The stand-in runs on the workers: they are told where it logs when they start.
        control = tempfile.mkdtemp(prefix="farm-frames-control-")
        cls.log = os.path.join(control, "frames.log")
        cls.broken = os.path.join(control, "broken_frame")
        cls.cluster = LoopbackCluster(workers=2, env={"FARM_STAND_IN_LOG": cls.log,
                                                      "FARM_STAND_IN_BROKEN": cls.broken})

    @classmethod
    def tearDownClass(cls):
        cls.cluster.close()

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-frames-")
        for path in (self.log, self.broken):
            if os.path.exists(path):
                os.remove(path)

    def references(self, gridrt, scene, frames, pattern):
        for k in frames:
            r = run([gridrt, *scene, *SIZE, "--frames", f"{k}:{k}", "--fps", str(FPS), "-q",
                     "-o", pattern])
            self.assertEqual(r.returncode, 0, r.stderr)

    def expect_sequence(self, gridrt, tiles, scene=()):
        ref = os.path.join(self.folder, "ref_%04d.png")
        out = os.path.join(self.folder, "out_%04d.png")
        self.references(gridrt, scene, range(FRAMES), ref)
        r = run(farm(self.cluster, *scene, "--frames", f"0:{FRAMES - 1}", "--tiles", tiles,
                     *SIZE, "--fps", str(FPS), "-o", out, gridrt=gridrt))
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
        self.expect_sequence(GRIDRT, "2x1", [animated_default_scene(self.folder)])

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

    def test_a_failed_sequence_keeps_its_finished_frames_and_resume_completes_it(self):
        last = 5
        ref = os.path.join(self.folder, "ref_%04d.png")
        out = os.path.join(self.folder, "out_%04d.png")
        self.references(STAND_IN, (), range(last + 1), ref)
        with open(self.broken, "w") as f:
            f.write(str(last))
        job = farm(self.cluster, "--frames", f"0:{last}", *SIZE, "-o", out, gridrt=STAND_IN)
        r = run(job)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr, f"gridrt: frame {last} cannot be rendered (the test's "
                                   "broken frame)\n")
        written = sorted(n for n in os.listdir(self.folder) if n.startswith("out_"))
        self.assertNotIn(os.path.basename(out % last), written)
        # Frames go out in order, one task at a time per worker, so the broken last frame's
        # second failure comes after the others have finished.
        self.assertTrue(written, "no finished frame was kept")
        for name in written:  # each a whole frame: nothing partial, no tiles left
            self.assertEqual(image_bytes(os.path.join(self.folder, name)),
                             image_bytes(os.path.join(self.folder, name.replace("out", "ref"))))
        self.assertFalse([n for n in os.listdir(self.folder) if n.startswith(".")])
        missing = [k for k in range(last + 1) if not os.path.exists(out % k)]
        os.remove(self.broken)
        os.remove(self.log)
        r = run(job + ["--resume"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.log) as f:
            self.assertEqual(sorted(int(line) for line in f), missing)
        for k in range(last + 1):
            self.assertEqual(image_bytes(out % k), image_bytes(ref % k), f"frame {k}")


if __name__ == "__main__":
    unittest.main()
