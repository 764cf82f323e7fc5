"""What the farm's tests share: the paths ctest gives them, a Dask cluster on loopback (a
scheduler and worker processes that stop by themselves), and bounded subprocess runs."""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("GRIDRT_SOURCE_DIR", os.path.dirname(os.path.dirname(HERE)))
GRIDRT = os.environ.get("GRIDRT_BINARY", os.path.join(SOURCE, "build", "gridrt"))
MERGE_TILES = os.environ.get("GRIDRT_MERGE_TILES",
                             os.path.join(os.path.dirname(GRIDRT), "tools", "gridrt-merge-tiles"))
FARM = os.path.join(SOURCE, "tools", "gridrt-farm")
STAND_IN = os.path.join(HERE, "anim_stand_in.py")
BROKEN_HERE = os.path.join(HERE, "broken_here_gridrt.py")
PYTHON = sys.executable

RUN_SECONDS = 180       # the longest any one command of a test may take
START_SECONDS = 60      # the longest the scheduler and workers may take to come up
SCHEDULER_IDLE = "600s"  # a scheduler left behind by a crashed test stops after this
WORKER_ORPHAN = "30s"    # a worker whose scheduler is gone stops after this
SIZE = ["--width", "64", "--height", "48"]  # small: a task takes a fraction of a second


def run(argv, **kwargs):
    return subprocess.run(argv, capture_output=True, text=True, timeout=RUN_SECONDS, **kwargs)


def file_bytes(path):
    with open(path, "rb") as f:
        return f.read()


class LoopbackCluster:
    """A Dask scheduler and `workers` worker processes (no nanny: a killed worker stays
    dead) on 127.0.0.1, each in its own process group; close() ends them, and they end by
    themselves after SCHEDULER_IDLE / WORKER_ORPHAN if a test dies first."""

    def __init__(self, workers=2, env=None, worker_env=None):
        self.env = dict(os.environ, **(env or {}))
        worker_env = worker_env or [{}] * workers
        self.folder = tempfile.mkdtemp(prefix="farm-cluster-")
        self.scheduler_file = os.path.join(self.folder, "scheduler.json")
        self.processes = []
        self.scheduler = self._start(
            [PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port",
             "0", "--no-dashboard", "--scheduler-file", self.scheduler_file, "--idle-timeout",
             SCHEDULER_IDLE], "scheduler")
        self.address = self._wait_for_address()
        self.workers = [self._start(
            [PYTHON, "-m", "distributed.cli.dask_worker", "--scheduler-file", self.scheduler_file,
             "--nthreads", "1", "--no-nanny", "--no-dashboard", "--host", "127.0.0.1",
             "--death-timeout", WORKER_ORPHAN,
             "--local-directory", os.path.join(self.folder, f"worker{k}")], f"worker{k}",
            worker_env[k]) for k in range(workers)]
        self._wait_for_workers(workers)

    def _start(self, argv, name, extra_env=None):
        log = open(os.path.join(self.folder, name + ".log"), "w")
        p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
                             env=dict(self.env, **(extra_env or {})))
        self.processes.append(p)
        return p

    def _wait_for_address(self):
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline:
            try:
                with open(self.scheduler_file) as f:
                    return json.load(f)["address"]
            except (OSError, ValueError, KeyError):
                time.sleep(0.1)
        self.close()
        raise RuntimeError("the Dask scheduler did not start")

    def _wait_for_workers(self, count):
        from distributed import Client
        with Client(self.address, timeout="30s") as client:
            client.wait_for_workers(count, timeout=START_SECONDS)

    def kill(self, process):
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=RUN_SECONDS)

    def close(self):
        for p in reversed(self.processes):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in self.processes:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()


def farm(cluster, *args, gridrt=GRIDRT):
    """The farm's command line on the test cluster."""
    return [FARM, "--scheduler", cluster.address, "--gridrt", gridrt, "--merge-tiles",
            MERGE_TILES, *args]


def exr_without_capture_date(data):
    """An EXR file's bytes without its capDate header attribute (the time OpenImageIO
    wrote it), so two files of the same pixels compare equal byte for byte. Header: magic
    and version (8 bytes), then attributes (name NUL, type NUL, int32 size, value) up to a
    NUL byte."""
    import struct
    out, k = [data[:8]], 8
    while data[k] != 0:
        name_end = data.index(b"\0", k)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        end = type_end + 5 + size
        if data[k:name_end] != b"capDate":
            out.append(data[k:end])
        k = end
    out.append(data[k:])
    return b"".join(out)


def image_bytes(path):
    """The file's bytes, an EXR's without its capture date."""
    data = file_bytes(path)
    return exr_without_capture_date(data) if path.lower().endswith(".exr") else data
