"""gridrt --version names its build, which the farm compares across workers: the build line
is the SHA-256 of the executable's bytes, the kernels line the SHA-256 of the kernel sources
embedded in it (each path under kernels/, a newline and its text, in path order)."""
import glob
import hashlib
import os
import unittest

from farm_support import GRIDRT, SOURCE, file_bytes, run


def version_lines():
    r = run([GRIDRT, "--version"])
    assert r.returncode == 0, r.stderr
    return dict(line.split(" ", 1) for line in r.stdout.splitlines())


class FarmBuildIdentity(unittest.TestCase):
    def test_version_names_the_executables_sha256_and_its_kernels(self):
        lines = version_lines()
        self.assertRegex(lines["gridrt"], r"^\d+\.\d+")
        self.assertEqual(lines["build"], hashlib.sha256(file_bytes(GRIDRT)).hexdigest())
        root = os.path.join(SOURCE, "kernels")
        sources = sorted(glob.glob(os.path.join(root, "*.cl")) +
                         glob.glob(os.path.join(root, "common", "*.h")))
        self.assertGreater(len(sources), 1)
        digest = hashlib.sha256()
        for path in sources:
            digest.update(os.path.relpath(path, root).encode() + b"\n" + file_bytes(path))
        self.assertEqual(lines["kernels"], digest.hexdigest())


if __name__ == "__main__":
    unittest.main()
