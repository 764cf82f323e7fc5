"""What the Python module's tests share: the module from the build (ctest puts
build/python on PYTHONPATH), the source tree, and a skip where no OpenCL device exists."""
import os
import unittest

import gridrt

SOURCE_DIR = os.environ.get("GRIDRT_SOURCE_DIR",
                            os.path.dirname(os.path.dirname(os.path.dirname(
                                os.path.abspath(__file__)))))


def model(name):
    return os.path.join(SOURCE_DIR, "scenes", "models", name)


class DeviceTestCase(unittest.TestCase):
    """Skips (ctest shows it skipped) when the machine has no OpenCL device."""

    @classmethod
    def setUpClass(cls):
        if not gridrt.devices():
            raise unittest.SkipTest("no OpenCL device (install pocl-opencl-icd)")
