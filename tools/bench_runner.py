"""What the benchmarks share: the paths of the build's programs, and one gridrt process whose
--stats-json comes back as a dict (tools/bench.py and the modules it imports, and
tools/bench_python.py)."""
import json
import os
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "scenes", "models")
# The source tree's own build.
BUILD_GRIDRT = os.path.join(ROOT, "build", "gridrt")
# GRIDRT_BINARY: another build's gridrt (a machine with another OpenCL device, say).
GRIDRT = os.environ.get("GRIDRT_BINARY") or BUILD_GRIDRT
# Embree 3 on the same rays, built where Embree is installed (tools/embree_peer.cpp).
EMBREE_PEER = os.path.join(ROOT, "build", "tools", "embree_peer")


def gridrt_stats(args, frames=None, env=None, binary=GRIDRT):
    """Runs `binary` with `args` (and --repeat `frames` when given), its image a PNG in a
    temporary folder (written after the timed frames, and without the image module), and
    returns its statistics with wall_s, the process's wall time and peak_mb, its peak
    resident memory. env: the process's environment (None: this one's)."""
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        cmd = [binary, *args]
        if frames is not None:
            cmd += ["--repeat", str(frames)]
        cmd += ["-q", "-o", os.path.join(tmp, "out.png"), "--stats-json", stats]
        started = time.monotonic()
        child = subprocess.Popen(cmd, env=env)
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.monotonic() - started
        if status != 0:
            raise subprocess.CalledProcessError(os.waitstatus_to_exitcode(status), cmd)
        with open(stats) as f:
            s = json.load(f)
    s["wall_s"] = wall
    s["peak_mb"] = usage.ru_maxrss / 1024.0  # kilobytes on Linux
    return s
