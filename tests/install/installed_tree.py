"""An install of the build into a temporary prefix, moved after installing, and commands
run from it with the source and build trees hidden: in a private mount namespace each tree
is covered by an empty tmpfs (root, or a user namespace), so nothing there can be read.
Where namespaces are refused the commands run with the trees in place, and the tests still
check through the dynamic loader's log that nothing is loaded from them."""
import os
import re
import shutil
import subprocess
import tempfile

SOURCE = os.environ["GRIDRT_SOURCE_DIR"]
BUILD = os.environ["GRIDRT_BUILD_DIR"]
BUILT_GRIDRT = os.environ["GRIDRT_BINARY"]
# The build's program cache, so the installed gridrt reuses the kernels the suite built.
CACHE = os.environ.get("GRIDRT_CACHE_DIR", "")
RUN_SECONDS = 180  # the longest any one command of a test may take
SIZE = ["--width", "64", "--height", "48"]  # small: a render takes a fraction of a second


def run(argv, **kwargs):
    return subprocess.run(argv, capture_output=True, text=True, timeout=RUN_SECONDS, **kwargs)


def file_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def without_loader_log(stderr):
    """stderr without the dynamic loader's LD_DEBUG lines ("  PID:\t..."), to read gridrt's."""
    return "\n".join(l for l in stderr.splitlines() if not re.match(r"^\s*\d+:\t", l))


def same_image(test, path, reference):
    """Asserts two renders equal: PNG files byte for byte; EXR files pixel for pixel with
    OpenImageIO's idiff and no tolerance (their headers carry the time they were written)."""
    if not path.endswith(".exr"):
        test.assertEqual(file_bytes(path), file_bytes(reference), path)
        return
    r = run(["idiff", "-a", "-fail", "0", "-warn", "0", path, reference])
    test.assertEqual(r.returncode, 0, f"{path} differs from {reference}: {r.stdout[-1500:]}")


def plain_environment(bin_dir):
    """The caller's environment with PATH reduced to bin_dir and the system's folders (no
    build tree on it) and no library path."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("LD_")}
    env["PATH"] = os.pathsep.join([bin_dir, "/usr/local/bin", "/usr/bin", "/bin"])
    return env


class HiddenTrees:
    """Runs commands with SOURCE and BUILD covered, the program cache bind-mounted first
    to a folder outside them."""

    def __init__(self, scratch):
        self.scratch = scratch
        self.cache = os.path.join(scratch, "program-cache")
        os.makedirs(self.cache)
        self.hidden, self.why_not = self._probe()

    def _script(self):
        lines = []
        if CACHE and os.path.isdir(CACHE):
            lines.append(f'mount --bind "{CACHE}" "{self.cache}"')
        for tree in (BUILD, SOURCE):  # the build first: it is often inside the source
            lines.append(f'mount -t tmpfs -o size=1m gridrt-hidden "{tree}"')
        return " && ".join(lines) + ' && exec "$@"'

    def _probe(self):
        probe = self.command(["test", "!", "-e", BUILT_GRIDRT], hidden=True)
        try:
            r = run(probe)
        except OSError as e:
            return False, str(e)
        if r.returncode == 0:
            return True, None
        return False, (r.stderr.strip().splitlines() or ["unshare failed"])[-1]

    def environment(self, bin_dir):
        """plain_environment(bin_dir) with the program cache where these commands see it."""
        env = plain_environment(bin_dir)
        if CACHE:
            env["GRIDRT_CACHE_DIR"] = self.cache if self.hidden else CACHE
        return env

    def command(self, argv, hidden=None):
        if hidden is None:
            hidden = self.hidden
        if not hidden:
            return argv
        return ["unshare", "--mount", "--propagation", "private", "sh", "-c", self._script(),
                "hidden-trees", *argv]


class InstalledTree:
    """`cmake --install BUILD --prefix P` into a fresh folder, then P moved elsewhere (the
    installed programs may rely only on their own places)."""

    def __init__(self):
        self.scratch = tempfile.mkdtemp(prefix="gridrt-install-test-")
        try:
            self._install()
        except BaseException:
            self.close()
            raise

    def _install(self):
        for tree in (SOURCE, BUILD):
            if os.path.realpath(self.scratch).startswith(os.path.realpath(tree) + os.sep):
                raise RuntimeError(f"the temporary folder {self.scratch} lies inside {tree}")
        first = os.path.join(self.scratch, "first-prefix")
        r = run(["cmake", "--install", BUILD, "--prefix", first])
        if r.returncode != 0:
            raise RuntimeError(f"cmake --install failed: {r.stderr.strip()}")
        self.prefix = os.path.join(self.scratch, "moved-prefix")
        os.rename(first, self.prefix)
        self.bin = os.path.join(self.prefix, "bin")
        self.trees = HiddenTrees(self.scratch)
        self.env = self.trees.environment(self.bin)

    def path(self, *parts):
        return os.path.join(self.prefix, *parts)

    def out(self, name):
        return os.path.join(self.scratch, name)

    def run(self, argv, env=None):
        """argv run from the installed tree, the trees hidden where possible, in scratch."""
        return run(self.trees.command(argv), env=env or self.env, cwd=self.scratch)

    def close(self):
        shutil.rmtree(self.scratch, ignore_errors=True)
