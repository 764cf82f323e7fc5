"""`pip install .` into a fresh virtual environment, then the module, the programs and the
farm's command from there. A whole build of the project (minutes to tens of minutes), so
it runs only with GRIDRT_TEST_PIP=1 and is skipped otherwise; it needs PyPI
(scikit-build-core, pybind11, numpy)."""
import os
import subprocess
import sys
import tempfile
import unittest

from python_support import SOURCE_DIR


@unittest.skipUnless(os.environ.get("GRIDRT_TEST_PIP") == "1",
                     "a whole build: set GRIDRT_TEST_PIP=1 to run it")
class PipInstall(unittest.TestCase):
    def test_pip_install_gives_the_module_and_the_commands(self):
        with tempfile.TemporaryDirectory() as folder:
            venv = os.path.join(folder, "venv")
            subprocess.run([sys.executable, "-m", "venv", venv], check=True)
            bin_dir = os.path.join(venv, "bin")
            subprocess.run([os.path.join(bin_dir, "pip"), "install", "--quiet", SOURCE_DIR],
                           check=True)
            environment = dict(os.environ)
            environment.pop("PYTHONPATH", None)  # the installed module, not the build's
            probe = ("import gridrt, numpy as np; "
                     "s = gridrt.Scene([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]); "
                     "print(s.intersect([[0.2, 0.2, 1]], [[0, 0, -1]]).prim[0], "
                     "gridrt.render(None, width=16, height=12).shape, gridrt.__file__)")
            out = subprocess.run([os.path.join(bin_dir, "python"), "-c", probe], check=True,
                                 capture_output=True, text=True, env=environment,
                                 cwd=folder).stdout
            self.assertIn("0 (12, 16, 3)", out)
            self.assertIn(venv, out)
            image = os.path.join(folder, "x.exr")
            subprocess.run([os.path.join(bin_dir, "gridrt"), "-q", "--width", "16", "--height",
                            "12", "-o", image], check=True, env=environment, cwd=folder)
            self.assertTrue(os.path.getsize(image) > 0)
            for command in ("gridrt-merge-tiles", "gridrt-farm"):
                self.assertTrue(os.access(os.path.join(bin_dir, command), os.X_OK), command)
            # Without the [farm] extra (Dask), the farm's command says so in one line.
            farm = subprocess.run([os.path.join(bin_dir, "gridrt-farm"), "--help"],
                                  capture_output=True, text=True, env=environment, cwd=folder)
            self.assertEqual(farm.returncode, 1, farm.stderr)
            self.assertEqual(len(farm.stderr.strip().splitlines()), 1, farm.stderr)
            self.assertIn("pip install 'gridrt[farm]'", farm.stderr)


if __name__ == "__main__":
    unittest.main()
