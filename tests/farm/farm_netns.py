"""Hosts for the farm's tests as network namespaces (we need root and iproute2's `ip`): a
hub namespace holding a bridge, where the client runs, and one namespace per other host
(the scheduler, each worker), each joined to the bridge by a veth pair, on a /24 of its
own. Namespaces share the file system, not the network: a worker reaches the scheduler
only over its veth link, which a test can cut. Names carry the test process's id, so runs
side by side never meet; close() deletes every namespace made, also after a failure.

And the certificates of a TLS farm, made with openssl in a test's folder: a CA, a
certificate and key per role, and an unrelated CA's client certificate."""
import os
import shutil
import signal
import subprocess
import uuid

from farm_support import PYTHON, START_SECONDS, SCHEDULER_IDLE, WORKER_ORPHAN

SUBNET = "10.57.0"       # inside the namespaces only: no route of the machine's is touched
SCHEDULER_PORT = 8786    # the scheduler's namespace is its own: a fixed port is free
IP_SECONDS = 20          # the longest one `ip` or `openssl` command may take
# A lost worker is noticed when its heartbeats stop for this long (Dask's default is 5
# minutes), and a new connection to it is given up after the connect timeout (default
# 30 s). Open connections to it break after distributed.comm.timeouts.tcp (30 s), left
# as it is: at 12 s workers under load lost their scheduler with no link cut.
WORKER_TTL = "8s"  # loose enough that a busy worker on a loaded 2-core machine is kept
CONNECT_TIMEOUT = "3s"
LOG_TAIL_LINES = 30  # of the scheduler's log, in a failed test's message


def _run(argv):
    return subprocess.run(argv, capture_output=True, text=True, timeout=IP_SECONDS)


def namespaces_unavailable():
    """Why namespaces cannot be made here (a skip reason), or None."""
    if os.geteuid() != 0:
        return "network namespaces need root"
    if shutil.which("ip") is None:
        return "no `ip` (iproute2) to make network namespaces"
    if shutil.which("openssl") is None:
        return "no `openssl` to make the farm's certificates"
    probe = f"gridrt-farm-probe-{os.getpid()}"
    r = _run(["ip", "netns", "add", probe])
    if r.returncode != 0:
        return f"cannot make a network namespace: {r.stderr.strip()}"
    _run(["ip", "netns", "delete", probe])
    return None


class NamespaceNet:
    """The hub and one namespace per name of `hosts`; address(name) is its IPv4 address."""

    def __init__(self, hosts):
        self.tag = f"gridrt-farm-{os.getpid()}-{uuid.uuid4().hex[:4]}"
        self.made = []
        self.addresses = {"hub": f"{SUBNET}.1"}
        try:
            self._add("hub")
            self._ip("hub", "link", "add", "br0", "type", "bridge")
            self._ip("hub", "addr", "add", f"{SUBNET}.1/24", "dev", "br0")
            self._ip("hub", "link", "set", "br0", "up")
            for k, name in enumerate(hosts):
                self._add(name)
                self.addresses[name] = f"{SUBNET}.{k + 2}"
                self._must(["ip", "link", "add", f"to-{name}"[:15], "netns", self.ns("hub"),
                            "type", "veth", "peer", "name", "eth0", "netns", self.ns(name)])
                self._ip("hub", "link", "set", f"to-{name}"[:15], "master", "br0", "up")
                self._ip(name, "addr", "add", f"{self.addresses[name]}/24", "dev", "eth0")
                self._ip(name, "link", "set", "eth0", "up")
        except BaseException:
            self.close()
            raise

    def ns(self, name):
        return f"{self.tag}-{name}"

    def address(self, name):
        return self.addresses[name]

    def inside(self, name, argv):
        """argv run in the namespace of `name` (`ip netns exec` execs it: same process)."""
        return ["ip", "netns", "exec", self.ns(name), *argv]

    def cut(self, name):
        """Takes the link of `name` down at the hub's end: its packets go nowhere, and no
        one on either side is told."""
        self._ip("hub", "link", "set", f"to-{name}"[:15], "down")

    def close(self):
        for ns in reversed(self.made):
            for pid in _run(["ip", "netns", "pids", ns]).stdout.split():
                try:
                    os.kill(int(pid), signal.SIGKILL)  # a process the test started in it
                except (ProcessLookupError, ValueError):
                    pass
            _run(["ip", "netns", "delete", ns])
        self.made = []

    def _add(self, name):
        self._must(["ip", "netns", "add", self.ns(name)])
        self.made.append(self.ns(name))
        self._ip(name, "link", "set", "lo", "up")

    def _ip(self, name, *args):
        self._must(["ip", "-n", self.ns(name), *args])

    def _must(self, argv):
        r = _run(argv)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(argv)}: {r.stderr.strip()}")


class Certificates:
    """openssl-made PEM files in `folder`: ca.pem (the farm's CA), ROLE.pem and ROLE.key
    for each role, signed by it, and other-ca.pem with stranger.pem/.key signed by that."""

    def __init__(self, folder, roles):
        self.folder = folder
        self._ca("ca")
        for role in roles:
            self._signed(role, "ca")
        self._ca("other-ca")
        self._signed("stranger", "other-ca")

    def path(self, name):
        return os.path.join(self.folder, name)

    def flags(self, role, ca="ca"):
        """The --tls-ca-file/--tls-cert/--tls-key flags of Dask's and the farm's commands."""
        return ["--tls-ca-file", self.path(f"{ca}.pem"), "--tls-cert", self.path(f"{role}.pem"),
                "--tls-key", self.path(f"{role}.key")]

    def _openssl(self, *args):
        r = _run(["openssl", *args])
        if r.returncode != 0:
            raise RuntimeError(f"openssl {args[0]}: {r.stderr.strip()}")

    def _ca(self, name):
        self._openssl("req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
                      "-nodes", "-days", "2", "-subj", f"/CN=gridrt farm test {name}",
                      "-keyout", self.path(f"{name}.key"), "-out", self.path(f"{name}.pem"))

    def _signed(self, role, ca):
        self._openssl("req", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
                      "-nodes", "-subj", f"/CN=gridrt farm test {role}",
                      "-keyout", self.path(f"{role}.key"), "-out", self.path(f"{role}.csr"))
        self._openssl("x509", "-req", "-in", self.path(f"{role}.csr"), "-days", "2",
                      "-CA", self.path(f"{ca}.pem"), "-CAkey", self.path(f"{ca}.key"),
                      "-CAcreateserial", "-out", self.path(f"{role}.pem"))


class NamespaceCluster:
    """A TLS scheduler in namespace "scheduler" and a worker (no nanny: one whose link is cut
    stays away) in each namespace of `workers`, with worker_env[name] added to its
    environment; logs in `folder`."""

    def __init__(self, net, certs, folder, workers, worker_env=None):
        self.net, self.folder, self.processes = net, folder, []
        self.env = dict(os.environ, DASK_DISTRIBUTED__SCHEDULER__WORKER_TTL=WORKER_TTL,
                        DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT=CONNECT_TIMEOUT)
        host = net.address("scheduler")
        self.address = f"tls://{host}:{SCHEDULER_PORT}"
        self.scheduler_file = os.path.join(folder, "scheduler.json")
        self._start("scheduler", [PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", host,
                                  "--port", str(SCHEDULER_PORT), "--protocol", "tls",
                                  "--no-dashboard", "--scheduler-file", self.scheduler_file,
                                  "--idle-timeout", SCHEDULER_IDLE, *certs.flags("scheduler")])
        self.workers = {}
        for name in workers:
            self.workers[name] = self._start(name, [
                PYTHON, "-m", "distributed.cli.dask_worker", self.address, "--nthreads", "1",
                "--no-nanny", "--no-dashboard", "--host", net.address(name), "--protocol", "tls",
                "--death-timeout", WORKER_ORPHAN, *certs.flags("worker"),
                "--local-directory", os.path.join(folder, f"{name}-space")],
                (worker_env or {}).get(name))
        self._wait_for_workers(certs, len(workers))

    def _start(self, name, argv, extra_env=None):
        log = open(os.path.join(self.folder, name + ".log"), "w")
        p = subprocess.Popen(self.net.inside(name, argv), stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True, env=dict(self.env, **(extra_env or {})))
        self.processes.append(p)
        return p

    def _wait_for_workers(self, certs, count):
        """Asked from the hub, over TLS with the client's certificate."""
        script = ("import sys; from distributed import Client, Security; "
                  "c = Client(sys.argv[1], timeout='30s', security=Security(tls_ca_file="
                  "sys.argv[2], tls_client_cert=sys.argv[3], tls_client_key=sys.argv[4], "
                  "require_encryption=True)); c.wait_for_workers(int(sys.argv[5]), "
                  f"timeout={START_SECONDS}); c.close()")
        r = subprocess.run(self.net.inside("hub", [
            PYTHON, "-c", script, self.address, certs.path("ca.pem"), certs.path("client.pem"),
            certs.path("client.key"), str(count)]), capture_output=True, text=True,
            timeout=START_SECONDS + 40)
        if r.returncode != 0:
            self.close()
            raise RuntimeError("the namespaced cluster did not start: " +
                               (r.stderr.strip().splitlines() or ["?"])[-1])

    def log_tail(self):
        with open(os.path.join(self.folder, "scheduler.log")) as f:
            return "".join(f.readlines()[-LOG_TAIL_LINES:])

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
