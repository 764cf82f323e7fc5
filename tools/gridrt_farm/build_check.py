"""One build everywhere. Before its first task every worker's gridrt says which build it is
(`gridrt --version`: the SHA-256 of its executable, which embeds the kernels); a worker of
another build, or whose gridrt cannot say, is left out of the job with a warning, or
refuses the job with --strict, so that a merged frame never mixes builds. The job's build
is that of the gridrt here; where none runs here, the one most workers of the first round
run."""
import collections
import sys

from . import worker_task

SHOWN_HEX = 16  # the digits of a build id shown in messages (the JSON has all 64)


class BuildRefused(Exception):
    """--strict and a worker of another build, or no build to go by: one line, exit 1."""


def short(build):
    return build[:SHOWN_HEX] if build else "unknown"


class BuildCheck:
    """The workers' builds as they come in: probe() asks every worker not yet asked,
    take() reads the answers, usable() is the workers of the job's build."""

    def __init__(self, client, candidates, expected, strict, job_id, stream=sys.stderr):
        self.client, self.candidates, self.strict = client, candidates, strict
        self.job_id, self.stream = job_id, stream
        self.expected = expected  # gridrt_identity() of the job's build, or None (undecided)
        self.probes = {}      # future -> worker
        self.accepted = set()
        self.left_out = {}    # worker -> why
        self.undecided = []   # identities waiting for the job's build to be decided

    def probe(self, alive):
        asked = set(self.probes.values()) | self.accepted | set(self.left_out) | \
            {i["worker"] for i in self.undecided}
        for worker in sorted(alive - asked):
            future = self.client.submit(worker_task.gridrt_identity, self.candidates,
                                        key=f"gridrt-build-{self.job_id}-{worker}", pure=False,
                                        workers=[worker], allow_other_workers=False,
                                        priority=10)
            self.probes[future] = worker
        for future, worker in list(self.probes.items()):
            if worker not in alive:  # gone before it answered: asked again if it returns
                future.cancel()
                del self.probes[future]

    def futures(self):
        return set(self.probes)

    def take(self, done):
        """Reads the finished probes among `done`; returns the futures it took."""
        taken = {f for f in done if f in self.probes}
        for future in taken:
            worker = self.probes.pop(future)
            try:
                identity = future.result()
            except Exception as e:  # the probe died with its worker, or could not run
                identity = {"worker": worker, "error": f"no answer ({type(e).__name__})"}
            identity["worker"] = worker
            if self.expected is None and "error" not in identity:
                self.undecided.append(identity)
            else:
                self._judge(identity)
        return taken

    def decide(self):
        """Once the first round has answered: the job's build, the one most workers run."""
        if self.expected is None and self.undecided:
            counts = collections.Counter(i["build"] for i in self.undecided).most_common()
            if len(counts) > 1 and counts[0][1] == counts[1][1]:
                raise BuildRefused("the workers run different gridrt builds ("
                                   + ", ".join(short(b) for b, _ in counts) + ") and none "
                                   "runs here to choose: give --gridrt a gridrt here")
            self.expected = next(i for i in self.undecided if i["build"] == counts[0][0])
        for identity in self.undecided:
            self._judge(identity)
        self.undecided = []

    def first_round_done(self):
        return not self.probes

    def usable(self, alive):
        return self.accepted & alive

    def _judge(self, identity):
        worker = identity["worker"]
        if "error" in identity:
            why = identity["error"]
        elif identity["build"] != self.expected["build"]:
            why = (f"its gridrt {identity['version']} is build {short(identity['build'])}, "
                   f"not the job's {short(self.expected['build'])}")
        else:
            self.accepted.add(worker)
            return
        if self.strict:
            raise BuildRefused(f"worker {worker}: {why}: job refused (--strict)")
        self.left_out[worker] = why
        print(f"gridrt-farm: worker {worker} left out of the job: {why}", file=self.stream)
