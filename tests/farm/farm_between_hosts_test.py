"""The farm between hosts: the scheduler and two workers each in a network namespace of its
own (farm_netns.py), the client in a fourth, all over TLS with certificates made by openssl
for the test. A job is the single render bit for bit; clients without the farm's
certificate are refused and nothing runs; a worker of another gridrt build is left out
(and --strict refuses the job); a worker whose link is cut mid-job loses nothing. Skipped,
with the reason, where namespaces cannot be made."""
import os
import shutil
import subprocess
import tempfile
import time
import unittest

import psutil

from farm_netns import Certificates, NamespaceCluster, NamespaceNet, namespaces_unavailable
from farm_support import (FARM, GRIDRT, HERE, MERGE_TILES, PYTHON, RUN_SECONDS, SIZE,
                          file_bytes, image_bytes, run)

WORKER_GRIDRT = os.path.join(HERE, "worker_gridrt.py")
TRY_CLIENT = os.path.join(HERE, "try_dask_client.py")
REFUSED = 3  # try_dask_client.py's exit status when it cannot reach the scheduler
POLL_SECONDS = 0.005  # how often the test looks for a gridrt under a worker
FARM_CONNECT_SECONDS = "3"  # the farm's --connect-timeout here: the network is one bridge


def lines(path):
    return file_bytes(path).decode().splitlines() if os.path.exists(path) else []


def renders(path):
    """The gridrt runs a worker's log holds, its --version probes left aside."""
    return [l for l in lines(path) if l != "--version"]


def rendering(process):
    """Whether the worker runs gridrt on a tile now (not gridrt --version)."""
    try:
        return any(c.name() == "gridrt" and "--crop" in c.cmdline()
                   for c in psutil.Process(process.pid).children(True))
    except psutil.NoSuchProcess:
        return False


class FarmBetweenHosts(unittest.TestCase):
    def setUp(self):
        reason = namespaces_unavailable()
        if reason:
            self.skipTest(reason)
        self.folder = tempfile.mkdtemp(prefix="farm-hosts-")
        self.addCleanup(shutil.rmtree, self.folder, True)
        self.certs = Certificates(self.folder, ["scheduler", "worker", "client"])
        self.net = NamespaceNet(["scheduler", "w1", "w2"])
        self.addCleanup(self.net.close)
        self.logs = {w: os.path.join(self.folder, f"{w}-gridrt.log") for w in ("w1", "w2")}

    def start(self, worker_env=None):
        env = {w: dict({"FARM_WORKER_LOG": self.logs[w]}, **(worker_env or {}).get(w, {}))
               for w in self.logs}
        self.cluster = NamespaceCluster(self.net, self.certs, self.folder, ["w1", "w2"], env)
        self.addCleanup(self.cluster.close)

    def farm(self, *args, role="client", ca="ca"):
        return self.net.inside("hub", [
            FARM, "--scheduler", self.cluster.address, *self.certs.flags(role, ca),
            "--connect-timeout", FARM_CONNECT_SECONDS, "--gridrt", WORKER_GRIDRT,
            "--merge-tiles", MERGE_TILES, *args])

    def single(self, name, *flags):
        path = os.path.join(self.folder, name)
        r = run([GRIDRT, *flags, "-q", "-o", path])
        self.assertEqual(r.returncode, 0, r.stderr)
        return image_bytes(path)

    def test_a_tls_job_between_hosts_is_the_single_render(self):
        self.start()
        out = os.path.join(self.folder, "farm.exr")
        r = run(self.farm("--tiles", "2x2", *SIZE, "--spp", "2", "-o", out))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(image_bytes(out), self.single("single.exr", *SIZE, "--spp", "2"))
        self.assertIn("on 2 workers", r.stderr)
        self.assertEqual(len(renders(self.logs["w1"])) + len(renders(self.logs["w2"])), 4)

    def test_clients_without_the_farms_certificate_are_refused_and_nothing_runs(self):
        self.start()
        plain = self.cluster.address.replace("tls://", "tcp://")
        c = self.certs.path
        attempts = {  # what each stranger shows the scheduler
            "no TLS": [plain],
            "no certificate": [self.cluster.address, "--ca", c("ca.pem")],
            "another CA's certificate": [self.cluster.address, "--ca", c("ca.pem"),
                                         "--cert", c("stranger.pem"), "--key", c("stranger.key")],
        }
        markers = {how: os.path.join(self.folder, f"ran-{k}") for k, how in enumerate(attempts)}
        tries = {how: subprocess.Popen(self.net.inside("hub", [PYTHON, TRY_CLIENT, argv[0],
                                                               markers[how], *argv[1:]]),
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for how, argv in attempts.items()}
        out = os.path.join(self.folder, "farm.png")
        r = run(self.farm("--tiles", "2x2", *SIZE, "-o", out, role="stranger", ca="other-ca"))
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("cannot reach the scheduler", r.stderr)
        for how, p in tries.items():
            _, err = p.communicate(timeout=RUN_SECONDS)
            self.assertEqual(p.returncode, REFUSED, f"{how}: {err}")
            self.assertFalse(os.path.exists(markers[how]), how)
        self.assertFalse(os.path.exists(out))
        self.assertEqual(lines(self.logs["w1"]) + lines(self.logs["w2"]), [])  # no gridrt ran
        # The same client with the farm's certificate is let in and runs (the test can fail).
        admitted = os.path.join(self.folder, "ran-admitted")
        r = run(self.net.inside("hub", [PYTHON, TRY_CLIENT, self.cluster.address, admitted,
                                        "--ca", c("ca.pem"), "--cert", c("client.pem"),
                                        "--key", c("client.key")]))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.exists(admitted))

    def test_a_worker_of_another_build_is_left_out_and_strict_refuses_the_job(self):
        other = os.path.join(self.folder, "gridrt")  # a byte more: another build
        shutil.copy2(GRIDRT, other)
        with open(other, "ab") as f:
            f.write(b"\0")
        self.start({"w2": {"FARM_OTHER_GRIDRT": other}})
        out = os.path.join(self.folder, "farm.png")
        r = run(self.farm("--tiles", "2x2", *SIZE, "-o", out))
        self.assertEqual(r.returncode, 0, r.stderr)
        warning = [l for l in r.stderr.splitlines() if "left out of the job" in l]
        self.assertEqual(len(warning), 1, r.stderr)
        self.assertIn(self.net.address("w2"), warning[0])
        self.assertIn("1 left out", r.stderr)
        self.assertEqual(image_bytes(out), self.single("single.png", *SIZE))
        self.assertEqual(renders(self.logs["w2"]), [])  # it was asked its build, nothing else
        self.assertEqual(len(renders(self.logs["w1"])), 4)
        os.remove(out)
        r = run(self.farm("--strict", "--tiles", "2x2", *SIZE, "-o", out))
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertIn("job refused (--strict)", r.stderr)
        self.assertIn(self.net.address("w2"), r.stderr)
        self.assertFalse(os.path.exists(out))
        self.assertEqual(len(renders(self.logs["w1"])), 4)  # no task ran this time
        self.assertEqual(renders(self.logs["w2"]), [])

    def test_a_worker_whose_link_is_cut_mid_job_loses_nothing(self):
        self.start()
        flags = [*SIZE, "--spp", "4"]
        out = os.path.join(self.folder, "farm.exr")
        job = subprocess.Popen(self.farm("--tiles", "2x2", *flags, "-o", out),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        victim = self.cluster.workers["w1"]
        deadline = time.monotonic() + RUN_SECONDS
        while not rendering(victim):
            self.assertIsNone(job.poll(), "the job ended before the worker ran a tile")
            self.assertLess(time.monotonic(), deadline, "the worker never ran a tile")
            time.sleep(POLL_SECONDS)
        self.net.cut("w1")  # mid-tile: the worker lives on, unreachable
        try:
            _, err = job.communicate(timeout=RUN_SECONDS)
        except subprocess.TimeoutExpired:
            job.kill()
            _, err = job.communicate()
            self.fail(f"the job did not end: {err}\nscheduler: {self.cluster.log_tail()}")
        self.assertEqual(job.returncode, 0, err)
        self.assertIn("1 workers lost", err)
        self.assertIsNone(victim.poll())  # the worker was cut off, not killed
        self.assertEqual(image_bytes(out), self.single("single.exr", *flags))


if __name__ == "__main__":
    unittest.main()
