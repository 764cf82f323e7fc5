"""The Debian package: `cpack -G DEB` over this build (nothing rebuilt) into a temporary
folder; its control file and file list inspected; `dpkg -x` into a throwaway root and
gridrt run from there with the source and build trees hidden, rendering what the build's
gridrt renders. Never installed into this machine's own root."""
import glob
import os
import re
import shutil
import tempfile
import unittest

from installed_tree import (BUILD, BUILT_GRIDRT, SIZE, HiddenTrees, run, same_image,
                            without_loader_log)

# What the package must hold, under /usr.
FILES = ["usr/bin/gridrt", "usr/bin/gridrt-merge-tiles", "usr/bin/gridrt-farm",
         "usr/lib/gridrt/gridrt_image_codec.so", "usr/share/man/man1/gridrt.1",
         "usr/share/bash-completion/completions/gridrt", "usr/share/doc/gridrt/README.md",
         "usr/share/gridrt/python/gridrt_farm/main.py",
         "usr/share/zsh/vendor-completions/_gridrt"]
# Libraries the programs link, whose packages dpkg-shlibdeps must have named.
LINKED = {"libOpenCL.so.1": "ocl-icd-libopencl1", "libpng16.so.16": "libpng16-16"}


class Package(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for tool, package in (("dpkg-deb", "dpkg"), ("dpkg-shlibdeps", "dpkg-dev"),
                              ("file", "file")):
            if not shutil.which(tool):
                raise unittest.SkipTest(f"{tool} is not installed (Debian's {package}; "
                                        "tools/setup.sh installs it)")
        cls.scratch = tempfile.mkdtemp(prefix="gridrt-package-test-")
        cls.addClassCleanup(shutil.rmtree, cls.scratch, ignore_errors=True)
        r = run(["cpack", "-G", "DEB", "-B", cls.scratch], cwd=BUILD)
        if r.returncode != 0:
            raise AssertionError(f"cpack failed: {(r.stdout + r.stderr)[-2000:]}")
        debs = glob.glob(os.path.join(cls.scratch, "gridrt_*.deb"))
        assert len(debs) == 1, f"cpack made {debs}"
        cls.deb = debs[0]

    def control(self):
        r = run(["dpkg-deb", "--field", self.deb])
        self.assertEqual(r.returncode, 0, r.stderr)
        fields, key = {}, None
        for line in r.stdout.splitlines():
            if line.startswith(" ") and key:
                fields[key] += "\n" + line
            else:
                key, _, value = line.partition(":")
                fields[key] = value.strip()
        return fields

    def test_control_file_file_list_and_a_render_from_the_extracted_tree(self):
        # One test, so that the package is made once.
        self.check_control_file()
        self.check_file_list()
        self.check_extracted_tree_renders()

    def check_control_file(self):
        fields = self.control()
        self.assertEqual(fields["Package"], "gridrt")
        version = run([BUILT_GRIDRT, "--version"]).stdout.split()[-1]
        self.assertTrue(fields["Version"].startswith(version), fields["Version"])
        self.assertEqual(os.path.basename(self.deb),
                         f"gridrt_{fields['Version']}_{fields['Architecture']}.deb")
        depends = [d.strip() for d in fields["Depends"].split(",")]
        names = {re.split(r"[ (]", d)[0] for d in depends}
        self.assertIn("python3-distributed", names)
        self.assertIn("python3", names)
        # Each linked library's package, as the dependency on the shared library names it.
        for library, package in LINKED.items():
            self.assertTrue(any(re.match(package + r"\b", d) for d in depends),
                            f"no dependency for {library}: {fields['Depends']}")
        self.assertTrue(any(n.startswith("libopenimageio") for n in names), fields["Depends"])

    def check_file_list(self):
        r = run(["dpkg-deb", "--contents", self.deb])
        self.assertEqual(r.returncode, 0, r.stderr)
        listed = {line.split()[-1].lstrip("./") for line in r.stdout.splitlines()}
        for path in FILES:
            self.assertIn(path, listed)
        # Everything under /usr (the packaging prefix), nothing of /usr/local or the build.
        outside = [p for p in listed if p and not p.startswith("usr/") or "usr/local" in p]
        self.assertEqual(outside, [])

    def check_extracted_tree_renders(self):
        root = os.path.join(self.scratch, "root")
        r = run(["dpkg-deb", "-x", self.deb, root])
        self.assertEqual(r.returncode, 0, r.stderr)
        trees = HiddenTrees(self.scratch)
        env = trees.environment(os.path.join(root, "usr", "bin"))
        out, built = os.path.join(self.scratch, "deb.exr"), os.path.join(self.scratch, "built.exr")
        r = run(trees.command(["gridrt", "-q", "-o", out, *SIZE]),
                env=dict(env, LD_DEBUG="files"), cwd=self.scratch)
        self.assertEqual(r.returncode, 0, without_loader_log(r.stderr))
        module = os.path.join(root, "usr", "lib", "gridrt", "gridrt_image_codec.so")
        self.assertEqual(set(re.findall(r"file=(\S*gridrt_image_codec\.so)", r.stderr)), {module})
        r = run([BUILT_GRIDRT, "-q", "-o", built, *SIZE], env=env)
        self.assertEqual(r.returncode, 0, r.stderr)
        same_image(self, out, built)


if __name__ == "__main__":
    unittest.main()
