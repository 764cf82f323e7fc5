"""Faults on two loopback workers: a worker killed while it runs a tile loses nothing (the
frame is still the single render); a worker where gridrt fails has its tasks tried again
on the other; a scene gridrt cannot load ends the job with gridrt's own one-line error,
its exit status, and nothing written."""
import os
import tempfile
import time
import unittest

import psutil

from farm_support import (BROKEN_HERE, GRIDRT, RUN_SECONDS, SIZE, LoopbackCluster, farm,
                          image_bytes, run)
import subprocess

POLL_SECONDS = 0.005  # how often the test looks for a gridrt under the worker


def running_gridrt(process):
    try:
        return any(c.name() == "gridrt" for c in psutil.Process(process.pid).children(True))
    except psutil.NoSuchProcess:
        return False


class FarmFaults(unittest.TestCase):
    def setUp(self):
        self.cluster = LoopbackCluster(workers=2)
        self.addCleanup(self.cluster.close)
        self.folder = tempfile.mkdtemp(prefix="farm-faults-")

    def test_a_worker_killed_mid_job_loses_nothing(self):
        single = os.path.join(self.folder, "single.exr")
        farmed = os.path.join(self.folder, "farm.exr")
        flags = [*SIZE, "--spp", "4"]
        r = run([GRIDRT, *flags, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        job = subprocess.Popen(farm(self.cluster, "--tiles", "4x4", *flags, "-o", farmed),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        victim = self.cluster.workers[0]
        deadline = time.monotonic() + RUN_SECONDS
        while not running_gridrt(victim):
            self.assertIsNone(job.poll(), "the job ended before the worker ran a tile")
            self.assertLess(time.monotonic(), deadline, "the worker never ran a tile")
            time.sleep(POLL_SECONDS)
        self.cluster.kill(victim)  # the worker and the gridrt it runs, mid-tile
        out, err = job.communicate(timeout=RUN_SECONDS)
        self.assertEqual(job.returncode, 0, err)
        self.assertIn("1 workers lost", err)
        self.assertEqual(image_bytes(farmed), image_bytes(single))

    def test_tasks_gridrt_fails_on_one_worker_are_rendered_on_the_other(self):
        self.cluster.close()
        self.cluster = LoopbackCluster(workers=2, worker_env=[{"FARM_BROKEN_WORKER": "1"}, {}])
        self.addCleanup(self.cluster.close)
        single = os.path.join(self.folder, "single.png")
        farmed = os.path.join(self.folder, "farm.png")
        r = run([GRIDRT, *SIZE, "-q", "-o", single])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run(farm(self.cluster, "--tiles", "4x4", *SIZE, "-o", farmed, gridrt=BROKEN_HERE))
        self.assertEqual(r.returncode, 0, r.stderr)
        retried = int(r.stderr.split(" retried")[0].rsplit("(", 1)[1])
        self.assertGreater(retried, 0, r.stderr)  # the broken worker took some tasks first
        self.assertEqual(image_bytes(farmed), image_bytes(single))
        # With no second try allowed, the broken worker's failure ends the job in its words.
        os.remove(farmed)
        r = run(farm(self.cluster, "--tiles", "4x4", "--retries", "0", *SIZE, "-o", farmed,
                     gridrt=BROKEN_HERE))
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr, "gridrt: no OpenCL platform found (the test's broken worker)\n")
        self.assertEqual(sorted(os.listdir(self.folder)), ["single.png"])

    def test_a_bad_scene_fails_with_gridrts_error_and_writes_nothing(self):
        scene = os.path.join(self.folder, "broken.gltf")
        with open(scene, "w") as f:
            f.write('{"asset": {"version": "2.0"}, "meshes": [')  # cut short
        alone = run([GRIDRT, scene, *SIZE, "-o", os.path.join(self.folder, "alone.png")])
        self.assertEqual(alone.returncode, 1)
        self.assertEqual(os.listdir(self.folder), ["broken.gltf"])
        output = os.path.join(self.folder, "farm.png")
        r = run(farm(self.cluster, scene, "--tiles", "4x4", *SIZE, "-o", output))
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.splitlines(), alone.stderr.splitlines()[-1:])
        self.assertTrue(r.stderr.startswith("gridrt: "), r.stderr)
        self.assertEqual(os.listdir(self.folder), ["broken.gltf"])  # no image, no tiles

    def test_a_usage_error_of_gridrt_ends_the_job_with_exit_2(self):
        output = os.path.join(self.folder, "farm.png")
        r = run(farm(self.cluster, "--tiles", "2x2", *SIZE, "--spp", "many", "-o", output))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("--spp", r.stderr)
        self.assertEqual(os.listdir(self.folder), [])


if __name__ == "__main__":
    unittest.main()
