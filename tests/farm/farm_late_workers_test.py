"""Workers that join a job already running, on loopback: each is asked its gridrt build
before its first task; one of the job's build takes its share of the tiles, one of
another build is left out with a warning and renders nothing, and the frame is still the
single render."""
import os
import shutil
import subprocess
import tempfile
import time
import unittest

from farm_support import (GRIDRT, HERE, RUN_SECONDS, SIZE, LoopbackCluster, farm, file_bytes,
                          image_bytes, run)

WORKER_GRIDRT = os.path.join(HERE, "worker_gridrt.py")
POLL_SECONDS = 0.05  # how often the test looks at what the workers ran


def renders(path):
    """The gridrt runs a worker's log holds (FARM_WORKER_LOG), its --version probes aside."""
    lines = file_bytes(path).decode().splitlines() if os.path.exists(path) else []
    return [l for l in lines if l != "--version"]


class FarmLateWorkers(unittest.TestCase):
    def test_workers_joining_mid_job_are_asked_their_build_first(self):
        folder = tempfile.mkdtemp(prefix="farm-late-")
        self.addCleanup(shutil.rmtree, folder, True)
        logs = [os.path.join(folder, f"worker{k}.log") for k in range(3)]
        gate = os.path.join(folder, "gate")  # the first worker's tiles wait for it
        cluster = LoopbackCluster(workers=1, worker_env=[{"FARM_WORKER_LOG": logs[0],
                                                          "FARM_WORKER_GATE": gate}])
        self.addCleanup(cluster.close)
        other = os.path.join(folder, "gridrt")  # a byte more: another build
        shutil.copy2(GRIDRT, other)
        with open(other, "ab") as f:
            f.write(b"\0")
        flags = [*SIZE, "--spp", "2"]
        out = os.path.join(folder, "farm.exr")
        job = subprocess.Popen(farm(cluster, "--tiles", "4x4", *flags, "-o", out,
                                    gridrt=WORKER_GRIDRT),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + RUN_SECONDS
        while not renders(logs[0]):  # the first worker has its first tile, held at the gate
            self.assertIsNone(job.poll(), "the job ended before it began")
            self.assertLess(time.monotonic(), deadline)
            time.sleep(POLL_SECONDS)
        cluster.add_worker({"FARM_WORKER_LOG": logs[1]})
        cluster.add_worker({"FARM_WORKER_LOG": logs[2], "FARM_OTHER_GRIDRT": other})
        while not all(os.path.exists(log) for log in logs[1:]):  # asked their build
            self.assertIsNone(job.poll(), "the job ended while its first tile waited")
            self.assertLess(time.monotonic(), deadline)
            time.sleep(POLL_SECONDS)
        with open(gate, "w"):
            pass
        _, err = job.communicate(timeout=RUN_SECONDS)
        self.assertEqual(job.returncode, 0, err)
        self.assertGreater(len(renders(logs[1])), 0, "the late worker of the build took no tile")
        self.assertEqual(file_bytes(logs[1]).decode().splitlines()[0], "--version")
        self.assertEqual(renders(logs[2]), [])
        self.assertEqual(len(renders(logs[0])) + len(renders(logs[1])), 16)
        self.assertEqual(len([l for l in err.splitlines() if "left out of the job" in l]), 1, err)
        single = os.path.join(folder, "single.exr")
        r = run([GRIDRT, *flags, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(image_bytes(out), image_bytes(single))


if __name__ == "__main__":
    unittest.main()
