"""bench.py farm: the render farm (tools/gridrt-farm) on a local Dask cluster of this
machine. Three measurements, each the median of `rounds` rounds:
- the cost of a task: a job of 64 tiny tiles (8x6 pixels of the 64x48 default scene) on one
  worker: the worker's time per task (a gridrt process: start, scene, kernels from the
  cache, a window, the file) against gridrt's own frame time in it, and Dask's share
  (the job's time per task minus the worker's);
- throughput against the number of workers: one frame (the default scene, 1280x960,
  --spp 16) as 4x4 tiles on 1, 2 and 4 local workers, against one gridrt process alone;
- the model of the speed-up on N machines (docs/farm.md) from those figures:
  T(N) = ceil(tasks / N) * (task overhead + frame / tasks) + merge, against the frame alone.
"""
import json
import math
import os
import statistics
import subprocess
import tempfile
import time

from bench_runner import BUILD_GRIDRT, ROOT, gridrt_stats

FARM = os.path.join(ROOT, "tools", "gridrt-farm")
OVERHEAD_JOB = ["--width", "64", "--height", "48", "--tiles", "8x8"]
THROUGHPUT_FRAME = ["--width", "1280", "--height", "960", "--spp", "16"]
THROUGHPUT_TILES = "4x4"
WORKER_COUNTS = [1, 2, 4]
MODEL_MACHINES = [1, 2, 4, 8, 16, 32, 64]


def run_farm(args, workers):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "farm.json")
        started = time.monotonic()
        subprocess.run([FARM, "--workers", str(workers), *args, "-q", "-o",
                        os.path.join(tmp, "out.png"), "--farm-stats", stats], check=True)
        wall = time.monotonic() - started
        with open(stats) as f:
            s = json.load(f)
    s["wall_s"] = wall  # the process: the local cluster's start and stop too
    return s


def run_alone(args):
    # The source tree's build, the one the farm's workers run here (tools/gridrt_farm).
    return gridrt_stats(args, binary=BUILD_GRIDRT)


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def bench_farm(frames, rounds):
    rows = []
    per_task, dask_share, frame_ms, startup_ms, loads = [], [], [], [], []
    for _ in range(rounds):
        loads.append(load_average())
        s = run_farm(OVERHEAD_JOB, 1)
        per_task.append(s["task_seconds_median"])
        frame_ms.append(s["gridrt_frame_ms_median"])
        startup_ms.append(s["gridrt_startup_ms_median"])
        dask_share.append(s["seconds"] / s["tasks"] - statistics.mean(s["task_seconds"]))
    overhead = {"label": "task cost (64 tiles of 8x6, 1 worker)", "workers": 1,
                "task_s": statistics.median(per_task),
                "gridrt_frame_ms_in_task": statistics.median(frame_ms),
                "gridrt_load_build_compile_ms_in_task": statistics.median(startup_ms),
                "dask_s_per_task": statistics.median(dask_share),
                "load_average": statistics.median(loads)}
    rows.append(overhead)
    print(f"farm task: {overhead['task_s'] * 1e3:.0f} ms a task (gridrt's frame "
          f"{overhead['gridrt_frame_ms_in_task']:.1f} ms and its load, build and compile "
          f"{overhead['gridrt_load_build_compile_ms_in_task']:.0f} ms of it), Dask "
          f"{overhead['dask_s_per_task'] * 1e3:.0f} ms a task; load {overhead['load_average']:.2f}",
          flush=True)

    alone = [run_alone(THROUGHPUT_FRAME) for _ in range(rounds)]
    alone_s = statistics.median(a["wall_s"] for a in alone)
    alone_frame_s = statistics.median(a["frame_ms"] for a in alone) / 1e3
    rays = alone[0]["rays"]["total"]
    rows.append({"label": "gridrt alone", "workers": 0, "job_s": alone_s,
                 "frame_s": alone_frame_s, "mrays_per_s": rays / alone_s / 1e6,
                 "load_average": load_average()})
    print(f"farm alone: {alone_s:.2f} s a process ({alone_frame_s:.2f} s the frame)", flush=True)
    merge_s = []
    for workers in WORKER_COUNTS:
        jobs = []
        for _ in range(rounds):
            loads.append(load_average())
            jobs.append(run_farm(THROUGHPUT_FRAME + ["--tiles", THROUGHPUT_TILES], workers))
        job_s = statistics.median(j["seconds"] for j in jobs)
        merge_s += [m for j in jobs for m in j["merge_seconds"]]
        rows.append({"label": f"farm, {workers} local workers", "workers": workers,
                     "job_s": job_s, "process_s": statistics.median(j["wall_s"] for j in jobs),
                     "mrays_per_s": rays / job_s / 1e6, "speedup_vs_alone": alone_s / job_s,
                     "load_average": statistics.median(loads[-rounds:])})
        print(f"farm {workers} workers: job {job_s:.2f} s, {rays / job_s / 1e6:.1f} Mrays/s, "
              f"{alone_s / job_s:.2f}x gridrt alone", flush=True)
    rows += model_rows(overhead["task_s"] + overhead["dask_s_per_task"], alone_frame_s,
                       statistics.median(merge_s), 16, alone_s)
    return rows


def model_rows(task_overhead_s, frame_s, merge_s, tasks, alone_s):
    """The speed-up on N machines of one gridrt process each, tiles of one frame."""
    rows = []
    for n in MODEL_MACHINES:
        t = math.ceil(tasks / n) * (task_overhead_s + frame_s / tasks) + merge_s
        rows.append({"label": f"model, {n} machines", "workers": n, "model_job_s": t,
                     "model_speedup_vs_alone": alone_s / t, "task_overhead_s": task_overhead_s,
                     "merge_s": merge_s, "tasks": tasks})
    return rows


def chart_farm(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    measured = [r for r in rows if "speedup_vs_alone" in r]
    model = [r for r in rows if "model_speedup_vs_alone" in r]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([r["workers"] for r in measured], [r["speedup_vs_alone"] for r in measured], "o-",
            label="measured: local workers on this machine")
    ax.plot([r["workers"] for r in model], [r["model_speedup_vs_alone"] for r in model], "s--",
            label="model: N machines, 16 tiles")
    ax.set(xscale="log", xlabel="workers / machines", ylabel="speed-up against gridrt alone",
           title="gridrt-farm: 1280x960 default scene, --spp 16, 4x4 tiles")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
