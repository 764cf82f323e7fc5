"""The farm's door and what passes it, without a cluster: tcp:// off loopback is refused
without --insecure, tls:// needs its three files, a worker gets only gridrt options the
farm knows (checked against gridrt --help) and writes only in its own folders, gridrt
found beside the farm or on PATH."""
import os
import re
import stat
import sys
import tempfile
import unittest

from farm_support import FARM, GRIDRT, SIZE, SOURCE, run

sys.path.insert(0, os.path.join(SOURCE, "tools"))
from gridrt_farm import command_line, executables, worker_task  # noqa: E402
from gridrt_farm.security import connection_security, is_loopback  # noqa: E402

OFF_LOOPBACK = "198.51.100.7"  # TEST-NET-2 (RFC 5737): never a machine of this network
CONNECT = ["--connect-timeout", "0.5"]  # nothing listens: give up soon
# An option of gridrt --help: "  -o,--output TEXT  ..." or "  --force   ..." (a flag: its
# description follows the names after two spaces or more).
HELP_OPTION = re.compile(r"^  (?:-\w,)?(--[a-z-]+)(?:,-\w)?( \S)?")


class FarmSecurity(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="farm-security-")
        self.out = os.path.join(self.folder, "out.png")

    def farm(self, *args):
        return run([FARM, *args, *SIZE, "-o", self.out])

    def assert_usage_error(self, r, *words):
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        self.assertTrue(r.stderr.startswith("gridrt-farm: "), r.stderr)
        for word in words:
            self.assertIn(word, r.stderr)

    def refusal(self, *args):
        """The one-line reason the farm's command line gives for refusing its connection
        (in this process: each farm process would spend a second importing Dask)."""
        with self.assertRaises(command_line.UsageError) as refused:
            connection_security(command_line.FarmCommand([*args, "-o", self.out]))
        return str(refused.exception)

    def test_tcp_off_loopback_is_refused_without_insecure(self):
        self.assert_usage_error(self.farm("--scheduler", f"tcp://{OFF_LOOPBACK}:8786"),
                                "not a loopback", "--insecure", "tls://")
        self.assertIn("not a loopback", self.refusal("--scheduler", f"{OFF_LOOPBACK}:8786"))
        r = self.farm("--scheduler", f"tcp://{OFF_LOOPBACK}:8786", "--insecure", *CONNECT)
        self.assertEqual(r.returncode, 1, r.stderr)  # let through, and nothing answers
        self.assertIn("cannot reach the scheduler", r.stderr)
        r = self.farm("--scheduler", "tcp://127.0.0.1:1", *CONNECT)  # other names: below
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("cannot reach the scheduler", r.stderr)
        self.assertEqual(os.listdir(self.folder), [])

    def test_loopback_is_told_from_other_addresses(self):
        for host in ("127.0.0.1", "127.8.9.10", "::1", "localhost"):
            self.assertTrue(is_loopback(host), host)
        for host in (OFF_LOOPBACK, "10.0.0.1", "::ffff:198.51.100.7", "no-such-host.invalid"):
            self.assertFalse(is_loopback(host), host)

    def test_tls_needs_its_three_files(self):
        tls = f"tls://{OFF_LOOPBACK}:8786"
        pem = os.path.join(self.folder, "a.pem")
        with open(pem, "w") as f:
            f.write("-----BEGIN CERTIFICATE-----\n")
        env_free = {k: v for k, v in os.environ.items() if not k.startswith("DASK_")}
        r = run([FARM, "--scheduler", tls, *SIZE, "-o", self.out], env=env_free)
        self.assert_usage_error(r, "--tls-ca-file", "--tls-cert", "--tls-key")
        self.assertIn("--tls-key missing", self.refusal("--scheduler", tls, "--tls-ca-file", pem,
                                                        "--tls-cert", pem))
        why = self.refusal("--scheduler", tls, "--tls-ca-file", pem, "--tls-cert", pem,
                           "--tls-key", os.path.join(self.folder, "none.key"))
        self.assertIn("--tls-key", why)
        self.assertIn("none.key", why)
        why = self.refusal("--scheduler", "tcp://127.0.0.1:1", "--tls-cert", pem)
        self.assertIn("--tls-cert", why)
        self.assertIn("tls://", why)
        self.assertIn("--scheduler", self.refusal("--insecure"))

    def test_only_gridrt_options_the_farm_knows_reach_a_worker(self):
        r = run([GRIDRT, "--help"])
        self.assertEqual(r.returncode, 0, r.stderr)
        flags, values = set(), set()
        for line in r.stdout.splitlines():
            m = HELP_OPTION.match(line)
            if m:
                (values if m.group(2) else flags).add(m.group(1))
        self.assertIn("--spp", values)
        self.assertIn("--alpha", flags)
        farm_own = {"--output", "--help", "--frames"}  # the farm's options of the same names
        known = command_line.FORWARDED_FLAGS | command_line.FORWARDED_VALUES | \
            set(command_line.REFUSED) | farm_own
        self.assertEqual({o for o in flags | values if o not in known}, set(),
                         "gridrt options the farm neither passes on nor refuses")
        self.assertEqual(values & command_line.FORWARDED_FLAGS, set())
        self.assertEqual(flags & command_line.FORWARDED_VALUES, set())
        self.assertEqual(set(command_line.REFUSED) & (command_line.FORWARDED_FLAGS |
                                                      command_line.FORWARDED_VALUES), set())
        self.assertEqual(command_line.REFUSED_FLAGS, flags & set(command_line.REFUSED))
        self.assert_usage_error(self.farm("--aov-file", "all.exr"), "--aov-file")
        self.assert_usage_error(self.farm("--no-such-option", "1"), "--no-such-option")
        self.assertEqual(os.listdir(self.folder), [])

    def test_a_worker_writes_only_in_its_own_folders(self):
        saved = tempfile.tempdir
        tempfile.tempdir = self.folder  # the worker's temporary folder
        self.addCleanup(setattr, tempfile, "tempdir", saved)
        spec = {"gridrt": [GRIDRT], "frame": None, "crop": "0,0,8,8", "scene_shown": None,
                "options": ["--width", "16", "--height", "12", "--aov-file",
                            os.path.join(self.folder, "elsewhere.exr")]}
        result = worker_task.render_tile(spec, None)
        self.assertEqual((result["ok"], result["code"]), (False, 2), result)
        self.assertIn("--aov-file", result["message"])
        spec["options"] = ["--width", "16", "--height", "12"]
        result = worker_task.render_tile(spec, None)
        self.assertTrue(result["ok"], result)
        self.assertEqual(os.listdir(self.folder), [])  # the task's folder is gone with it
        files = {"scene.gltf": b"{}", "buffers/b.bin": b"\0"}
        good = {"digest": worker_task.bundle_digest(files), "files": files, "main": "scene.gltf"}
        path = worker_task.scene_on_this_machine(good)
        self.assertEqual(path, os.path.join(self.folder, worker_task.SCENE_CACHE,
                                            good["digest"], "scene.gltf"))
        self.assertTrue(os.path.isfile(os.path.join(os.path.dirname(path), "buffers", "b.bin")))
        outside = dict(files, **{"../outside.bin": b"x"})
        for bad in ({**good, "digest": "0" * 32},  # not the files' digest
                    {**good, "files": outside, "digest": worker_task.bundle_digest(outside)},
                    {**good, "main": "../scene.gltf"}):
            with self.assertRaises(ValueError):
                worker_task.scene_on_this_machine(bad)
        self.assertFalse(os.path.exists(os.path.join(self.folder, "outside.bin")))

    def test_gridrt_is_found_beside_the_farm_else_in_the_tree_else_on_path(self):
        beside = os.path.join(self.folder, "bin")
        os.makedirs(beside)
        program = os.path.join(beside, "gridrt-farm")
        candidates = executables.gridrt_candidates(program)
        self.assertEqual(candidates, [os.path.join(beside, "gridrt"),
                                      os.path.join(SOURCE, "build", "gridrt"), "gridrt"])
        self.assertEqual(executables.gridrt_candidates(program, "x/gridrt"),
                         [os.path.abspath("x/gridrt")])
        os.symlink(GRIDRT, os.path.join(beside, "gridrt"))
        self.assertEqual(executables.first_executable(candidates), os.path.join(beside, "gridrt"))
        merger = os.path.join(beside, executables.MERGE_TILES)
        with open(merger, "w") as f:
            f.write("#!/bin/sh\n")
        os.chmod(merger, stat.S_IRWXU)
        self.assertEqual(executables.merge_tiles_for(os.path.join(beside, "gridrt"), program),
                         merger)
        on_path = os.path.join(self.folder, "path")
        os.makedirs(on_path)
        os.symlink(GRIDRT, os.path.join(on_path, "gridrt"))
        saved = os.environ["PATH"]
        os.environ["PATH"] = on_path
        try:
            self.assertEqual(executables.first_executable(
                [os.path.join(self.folder, "nowhere", "gridrt"), "gridrt"]),
                os.path.join(on_path, "gridrt"))
        finally:
            os.environ["PATH"] = saved


if __name__ == "__main__":
    unittest.main()
