"""gridrt.render against the command line: the same options give, bit for bit, the
pixels of the .exr the gridrt program writes (read with OpenImageIO's Python binding,
Debian's python3-openimageio)."""
import os
import subprocess
import tempfile
import unittest

import numpy as np

import gridrt
from python_support import DeviceTestCase, model

GRIDRT = os.environ.get("GRIDRT_BINARY", "")


def exr_pixels(path):
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    if image is None:
        raise RuntimeError(oiio.geterror())
    pixels = image.read_image(format="float")
    image.close()
    return pixels


class RenderEqualsCommandLine(DeviceTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        if not os.access(GRIDRT, os.X_OK):
            raise unittest.SkipTest("GRIDRT_BINARY does not name the gridrt program")
        try:
            import OpenImageIO  # noqa: F401
        except ImportError:
            raise unittest.SkipTest("no OpenImageIO Python binding (python3-openimageio)")

    def command_line_image(self, scene, flags):
        with tempfile.TemporaryDirectory() as folder:
            out = os.path.join(folder, "out.exr")
            arguments = [GRIDRT] + ([scene] if scene else []) + ["-q", "-o", out] + flags
            subprocess.run(arguments, check=True)
            return exr_pixels(out)

    def assert_same(self, scene, flags, **options):
        expected = self.command_line_image(scene, flags)
        got = gridrt.render(scene, **options)
        self.assertEqual(got.dtype, np.float32)
        self.assertEqual(got.shape, expected.shape)
        self.assertGreater(float(got.max()), 0.0, "a black image proves little")
        np.testing.assert_array_equal(got, expected)
        return got

    def test_whitted_frame_of_a_file(self):
        image = self.assert_same(model("bunny_res3.glb"),
                                 ["--width", "96", "--height", "64", "--max-depth", "2",
                                  "--spp", "2", "--background", "0.1,0.2,0.3"],
                                 width=96, height=64, max_depth=2, spp=2,
                                 background=(0.1, 0.2, 0.3))
        self.assertEqual(image.shape, (64, 96, 3))

    def test_default_scene_with_alpha(self):
        image = self.assert_same(None, ["--width", "80", "--height", "60", "--alpha"],
                                 width=80, height=60, alpha=True)
        self.assertEqual(image.shape, (60, 80, 4))

    def test_loaded_scene_and_crop_window(self):
        path = model("teapot.glb")
        flags = ["--width", "64", "--height", "48", "--crop", "8,4,40,30", "--crop-output",
                 "window", "--aa", "adaptive"]
        expected = self.command_line_image(path, flags)
        got = gridrt.render(gridrt.load(path), width=64, height=48, crop=(8, 4, 40, 30),
                            crop_output="window", aa="adaptive")
        self.assertEqual(got.shape, (26, 32, 3))
        np.testing.assert_array_equal(got, expected)


if __name__ == "__main__":
    unittest.main()
