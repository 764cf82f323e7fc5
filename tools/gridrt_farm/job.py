"""One farm job on a connected Dask client: a task per tile of each missing frame, handed
out in order (frames in turn, tiles in --tile-order) to the workers of the job's gridrt
build (build_check.py: every worker says its build before its first task), a few at a time
each, so that a worker which joins later takes its share; each result kept until its frame
is complete, then the frame merged and written. Faults:
- a worker that dies (or whose link is cut) takes its tasks with it; Dask runs them again
  on the other workers of the build (up to distributed.scheduler.allowed-failures deaths
  of one task), and tasks left with no worker alive are handed out again;
- gridrt failing a task (exit 1, or a crash) tries it again on a worker it has not failed
  on, up to --retries times; when none is left, or gridrt exits 2 (a usage error, the same
  everywhere), the job ends with gridrt's one-line message and exit status, the tiles of
  unfinished frames are removed, and the frames already written stay.
"""
import collections
import os
import statistics
import time
import uuid
import warnings

import cloudpickle

from . import cluster, worker_task
from .build_check import BuildCheck
from .merge import FrameTiles
from .progress import Progress
from .tiles import ordered, split

WAIT_SECONDS = 0.5  # the longest wait between two looks at the cluster
# Tasks handed to each worker of the job's build at once: one runs while the next waits
# there, so no worker waits for this client, and later workers still find tasks to take.
IN_FLIGHT_PER_WORKER = 2
# How long the job waits at first for one finished task's result, doubled at each wait
# that runs out (a large tile on a slow link still arrives): a result held by a worker whose
# link is cut cannot come until Dask gives the worker up and makes it again, and the job
# keeps looking at the cluster meanwhile.
FETCH_SECONDS = 5.0
AGAIN = "again"  # _finish(): the result is not here yet


class JobFailed(Exception):
    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


class Task:
    def __init__(self, order, frame_pos, frame, tile_index, tile):
        self.order, self.frame_pos, self.frame = order, frame_pos, frame
        self.tile_index, self.tile = tile_index, tile
        self.failed_on, self.attempts, self.workers = set(), 0, set()
        self.fetch_seconds = FETCH_SECONDS
        self.message = ""


class FarmJob:
    def __init__(self, client, command, size, scene, scene_shown, gridrt, expected,
                 merge_tiles):
        """gridrt: the candidate paths each worker resolves (executables.py); expected: the
        gridrt_identity() of the job's build, or None to take the workers' majority."""
        self.client, self.cmd = client, command
        self.width, self.height = size
        self.scene, self.scene_shown = scene, scene_shown
        self.gridrt, self.merge_tiles = gridrt, merge_tiles
        self.options = ["--width", str(self.width), "--height", str(self.height)]
        for flag, value in command.gridrt_options:
            self.options += [flag] if value is None else [flag, value]
        self.job_id = uuid.uuid4().hex[:8]
        self.builds = BuildCheck(client, gridrt, expected, command.strict, self.job_id)
        self.stats = {"tasks": 0, "retries": 0, "workers_lost": 0, "workers_seen": 0,
                      "workers_left_out": {}, "build": None, "gridrt_version": None,
                      "frames_written": 0, "frames_kept": 0, "rays": 0, "output": command.output,
                      "width": self.width, "height": self.height,
                      "tiles": list(command.tiles), "task_seconds": [], "gridrt_frame_ms": [],
                      "gridrt_startup_ms": [], "merge_seconds": [], "seconds": 0.0}

    def spec(self, task):
        return {"gridrt": self.gridrt, "options": self.options, "frame": task.frame,
                "crop": task.tile.crop(), "scene_shown": self.scene_shown}

    def submit(self, task, scene_ref, workers):
        task.attempts += 1
        task.workers = set(workers)
        self.submissions += 1  # every submission a key of its own, also after a cancel
        key = f"gridrt-{self.job_id}-{task.frame_pos}-{task.tile_index}-{self.submissions}"
        future = self.client.submit(worker_task.render_tile, self.spec(task), scene_ref,
                                    key=key, pure=False, priority=-task.order,
                                    workers=sorted(workers), allow_other_workers=False)
        self.owner[future.key] = task
        return future

    def run(self):
        started = time.monotonic()
        tiles = ordered(split(self.width, self.height, *self.cmd.tiles), self.width, self.height,
                        self.cmd.tile_order)
        frames = []
        for frame in self.cmd.frame_numbers():
            output = self.cmd.output_of(frame)
            if self.cmd.resume and _exists(output):
                self.stats["frames_kept"] += 1
            else:
                frames.append((frame, output))
        tasks = [Task(pos * len(tiles) + k, pos, frame, k, tile)
                 for pos, (frame, _) in enumerate(frames) for k, tile in enumerate(tiles)]
        self.stats["tasks"] = len(tasks)
        if not tasks:
            self.stats["seconds"] = time.monotonic() - started
            return self.stats
        # The task's module goes to the workers by value: they need no copy of the farm.
        cloudpickle.register_pickle_by_value(worker_task)
        self.owner, self.submissions = {}, 0
        self.frame_tiles = {pos: FrameTiles(output, len(tiles))
                            for pos, (_, output) in enumerate(frames)}
        pending, active = collections.deque(tasks), set()
        progress = Progress(len(tasks), len(frames), self.cmd.quiet)
        done_tasks, alone_since, seen, scene_ref = 0, None, set(), None
        first_round_over = False
        try:
            while pending or active:
                alive = cluster.alive_workers(self.client)
                seen |= alive
                self.builds.probe(alive)
                if alive and self.builds.first_round_done():
                    self.builds.decide()  # no task runs before the first workers answered
                    first_round_over = self.builds.expected is not None
                usable = self.builds.usable(alive) if first_round_over else set()
                if usable and scene_ref is None:
                    scene_ref = self._send_scene(usable)
                for future in [f for f in active if not self.owner[f.key].workers & alive]:
                    active.discard(future)  # its workers are gone: Dask would wait for them
                    future.cancel()
                    task = self.owner.pop(future.key)
                    task.attempts -= 1  # not a try of gridrt's: --retries counts those
                    pending.appendleft(task)
                while pending and len(active) < IN_FLIGHT_PER_WORKER * len(usable):
                    targets = usable - pending[0].failed_on
                    if not targets:
                        raise JobFailed(pending[0].message, 1)
                    active.add(self.submit(pending.popleft(), scene_ref, targets))
                done = self._wait(active | self.builds.futures())
                self.builds.take(done)
                for future in done & active:
                    retry = self._finish(future)
                    if retry is AGAIN:
                        continue  # Dask makes it again where it was lost; wait for it
                    active.discard(future)
                    if retry is not None:
                        pending.appendleft(retry)
                    else:
                        done_tasks += 1
                self.stats["workers_lost"] = len(seen - alive)
                alone_since = None if usable or self.builds.futures() else \
                    (alone_since or time.monotonic())
                patience = self.cmd.wait_for_workers
                if alone_since and time.monotonic() - alone_since > patience:
                    left = len(self.builds.left_out)
                    raise JobFailed(f"gridrt-farm: no worker of the job's gridrt build alive "
                                    f"for {patience:g} s (--wait-for-workers)"
                                    + (f"; {left} left out" if left else ""), 1)
                progress.update(done_tasks, self.stats["frames_written"], len(usable))
        except BaseException:
            self.client.cancel(list(active))
            for tiles_of_frame in self.frame_tiles.values():
                tiles_of_frame.discard()
            raise
        finally:
            progress.close()
        self.stats["workers_seen"] = len(seen)
        self.stats["workers_left_out"] = dict(self.builds.left_out)
        self.stats["build"] = self.builds.expected["build"]
        self.stats["gridrt_version"] = self.builds.expected["version"]
        self.stats["seconds"] = time.monotonic() - started
        return self.stats

    def _send_scene(self, usable):
        """What the tasks get as their scene: None (built-in), a path (--shared-scene), or
        the future of a task whose result is the scene's files: each worker fetches it once,
        and a copy lost with a worker is made again from the task (scattered data would be
        gone)."""
        if not isinstance(self.scene, dict):
            return self.scene
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=".*[Ll]arge object.*")
            return self.client.submit(worker_task.scene_data, self.scene,
                                      key=f"gridrt-scene-{self.job_id}", pure=False,
                                      priority=1, workers=sorted(usable),
                                      allow_other_workers=True)

    def _wait(self, active):
        from distributed import wait
        if not active:  # no worker to hand a task to yet
            time.sleep(WAIT_SECONDS)
            return set()
        try:
            return wait(list(active), timeout=WAIT_SECONDS, return_when="FIRST_COMPLETED").done
        except TimeoutError:
            return set()

    def _finish(self, future):
        """Handles a finished task; returns the task when it is to be tried again, AGAIN when
        its result could not be fetched yet, or None."""
        task = self.owner[future.key]
        try:
            result = future.result(timeout=task.fetch_seconds)
        except TimeoutError:  # its worker is out of reach, or its result lost with it
            task.fetch_seconds *= 2
            return AGAIN
        except Exception as e:  # Dask gave up: the task killed its workers (KilledWorker)
            task = self.owner.pop(future.key)
            raise JobFailed(f"gridrt-farm: {self._name(task)} was lost with every worker that "
                            f"ran it ({type(e).__name__})", 1) from None
        task = self.owner.pop(future.key)
        if not result["ok"]:
            return self._retry(task, result)
        self.stats["rays"] += result["rays"]
        self.stats["task_seconds"].append(result["seconds"])
        self.stats["gridrt_frame_ms"].append(result["frame_ms"])
        self.stats["gridrt_startup_ms"].append(result["load_ms"] + result["build_ms"] +
                                               result["compile_ms"])
        frame = self.frame_tiles[task.frame_pos]
        frame.add(task.tile_index, result["tile"])
        if frame.complete():
            merge_started = time.monotonic()
            try:
                frame.merge(self.merge_tiles)
            except Exception as e:
                raise JobFailed(f"gridrt-farm: {e}", 1) from None
            self.stats["merge_seconds"].append(time.monotonic() - merge_started)
            self.stats["frames_written"] += 1
        return None

    def _retry(self, task, result):
        code = result["code"]
        if code == 2:  # a usage error: every worker would say the same
            raise JobFailed(result["message"], 2)
        task.failed_on.add(result["worker"])
        task.message = result["message"]
        others = self.builds.usable(cluster.alive_workers(self.client)) - task.failed_on
        if task.attempts > self.cmd.retries or not others:
            raise JobFailed(result["message"], code if code > 0 else 1)
        self.stats["retries"] += 1
        return task

    def _name(self, task):
        frame = "" if task.frame is None else f" of frame {task.frame}"
        return f"tile {task.tile.crop()}{frame}"


def summary_numbers(stats):
    """Medians for the statistics file (the per-task lists stay beside them)."""
    out = dict(stats)
    for key in ("task_seconds", "gridrt_frame_ms", "gridrt_startup_ms", "merge_seconds"):
        values = stats[key]
        out[key + "_median"] = statistics.median(values) if values else None
    return out


def _exists(path):
    return os.path.isfile(path)
