#!/usr/bin/env python3
"""GridRT benchmark harness: runs a named set of renders and writes a CSV and a PNG chart.

Each figure is the median of --frames frames rendered after one warm-up frame (gridrt
--repeat), so scene loading and kernel compilation are excluded; they are reported in
their own columns (load_ms, compile_ms, build_ms).

    .venv/bin/python tools/bench.py paper     # the paper's experiment (bunny_res4, 320x240)
    .venv/bin/python tools/bench.py scaling   # triangles, image size, and every pass against threads
    .venv/bin/python tools/bench.py waves     # the Whitted frame by pass against its wave size (--wave-rays)
    .venv/bin/python tools/bench.py whitted   # full Whitted frames with shadows (median of 5 processes),
                                              # and the default and bunny frames with Embree tracing beside gridrt
    .venv/bin/python tools/bench.py targets   # the four speed targets, Embree beside
    .venv/bin/python tools/bench.py single    # one render per process: wall time, peak memory
    .venv/bin/python tools/bench.py adaptive  # uneven scenes: uniform grid, adaptive, Embree, in turns
    .venv/bin/python tools/bench.py dynamic   # moving scenes: rebuild + render per frame, gridrt and Embree
    .venv/bin/python tools/bench.py farm      # tools/gridrt-farm: task cost, workers, the model
    .venv/bin/python tools/bench.py packets   # a PE packet's device cost by part (kernel probe stages)
    .venv/bin/python tools/bench.py all
"""
import argparse
import csv
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile

from bench_farm import bench_farm, chart_farm
from bench_packets import bench_packets, chart_packets
from bench_runner import EMBREE_PEER, GRIDRT, MODELS, ROOT, gridrt_stats

# The paper's PE counts and the grids that give them (Nery et al., Tables III/IV).
PAPER_GRIDS = [(1, "1,1,1"), (2, "2,1,1"), (4, "2,2,1"), (8, "2,2,2"), (12, "3,2,2"),
               (18, "3,3,2"), (27, "3,3,3"), (36, "4,3,3"), (48, "4,4,3"), (64, "4,4,4"),
               (125, "5,5,5"), (216, "6,6,6")]
# The two figures the paper gives for this experiment (low-res bunny, 320x240, primary).
PAPER_POINTS = [("FPGA, 8 PEs (paper)", 8, 82000.0), ("GTX 465 CUDA, 27 blocks (paper)", 27, 1320.0)]


# gridrt's list time (lists_ms) by host pass: the lists' walk, the pairs' binning, bundling;
# and their names in the charts.
LIST_PASSES = ("walk_ms", "binning_ms", "bundling_ms")
PHASE_NAMES = {"walk_ms": "list walk", "binning_ms": "binning", "bundling_ms": "bundling"}


def run(args, frames):
    s = gridrt_stats(args, frames)
    # The tracing time by ray kind, flattened (trace_primary_ms, ...) so medians() takes it,
    # and gridrt's list time by host pass (walk_ms, binning_ms, bundling_ms).
    for key, value in s.get("trace", {}).items():
        s["trace_" + key] = value
    for key in LIST_PASSES:
        s[key] = s.get("lists", {}).get(key, 0.0)
    return s


def row(label, s, **extra):
    r = {"label": label, "accel": s["accel"], "triangles": s["triangles"],
         "width": s["width"], "height": s["height"], "rays": s["rays"]["total"],
         "frame_ms": s["frame_ms"], "lists_ms": s["lists_ms"],
         **{key: s.get(key, 0.0) for key in LIST_PASSES}, "kernel_ms": s["kernel_ms"],
         "kernel_device_ms": s.get("kernel_device_ms", 0.0),
         "transfer_device_ms": s.get("transfer_device_ms", 0.0),
         "reduce_ms": s["reduce_ms"], "shade_ms": s["shade_ms"],
         "mrays_per_s": s["mrays_per_s"], "tests_per_ray": s["tests_per_ray"],
         "tests_run_per_ray": s["tests_run_per_ray"],
         "load_ms": s["load_ms"], "compile_ms": s["compile_ms"], "build_ms": s["build_ms"]}
    grid = s.get("grid")
    if grid:
        r.update(grid_dims="x".join(map(str, grid["dims"])), voxels=grid["voxels"], pes=grid["pes"])
    load = s.get("pe_load")
    if load:
        r.update(pe_rays_mean=load["rays_mean"], pe_rays_max=load["rays_max"],
                 pe_tests_mean=load["tests_mean"], pe_tests_max=load["tests_max"])
    r.update(extra)
    return r


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def bench_paper(frames):
    scene = os.path.join(MODELS, "bunny_res4.glb")
    base = [scene, "--width", "320", "--height", "240", "--primary-only"]
    rows = []
    for accel in ["gridrt", "dda"]:
        for pes, grid in PAPER_GRIDS + [(0, "auto")]:
            s = run(base + ["--accel", accel, "--grid", grid], frames)
            rows.append(row(f"{accel} {grid}", s, paper_pes=pes, grid=grid))
            print(f"paper {accel:7s} grid {grid:6s}: {s['frame_ms']:8.2f} ms, "
                  f"{s['tests_per_ray']:7.1f} tests/ray ({s['tests_run_per_ray']:.1f} run)",
                  flush=True)
    s = run(base + ["--accel", "brute"], frames)
    rows.append(row("brute", s, paper_pes=1, grid="none"))
    print(f"paper brute: {s['frame_ms']:.2f} ms", flush=True)
    return rows


def chart_paper(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    for accel, marker, colour in [("gridrt", "o", "C0"), ("dda", "s", "C1")]:
        pts = [(r["voxels"], r["frame_ms"], r["tests_per_ray"], r["tests_run_per_ray"])
               for r in rows if r["accel"].startswith(accel) and r["grid"] != "auto"]
        a.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=colour,
               label=f"{accel} (this work)")
        b.plot([p[0] for p in pts], [p[2] for p in pts], marker=marker, color=colour,
               ls=":" if accel == "gridrt" else "-",
               label=f"{accel}: the voxels' triangles (the paper's count)")
        if accel == "gridrt":  # dda culls nothing: it runs every test it counts
            b.plot([p[0] for p in pts], [p[3] for p in pts], marker=marker, color=colour,
                   label="gridrt: tests run after culling")
        auto = [r for r in rows if r["accel"].startswith(accel) and r["grid"] == "auto"]
        if auto:
            a.scatter([auto[0]["voxels"]], [auto[0]["frame_ms"]], marker="*", s=150, zorder=5,
                      label=f"{accel} auto ({auto[0]['grid_dims']})")
    brute = [r for r in rows if r["accel"] == "brute"][0]
    a.axhline(brute["frame_ms"], color="grey", ls=":", label="brute force (device)")
    for label, pes, ms in PAPER_POINTS:
        a.scatter([pes], [ms], marker="x", s=80, label=label)
    a.set(xscale="log", yscale="log", xlabel="grid voxels (paper: PEs)", ylabel="frame time (ms)",
          title="bunny_res4, 320x240, primary rays")
    a.legend(fontsize=7)
    b.set(xscale="log", yscale="log", xlabel="grid voxels", ylabel="ray-triangle tests per ray",
          title="work per ray")
    b.axhline(brute["tests_per_ray"], color="grey", ls=":", label="brute force")
    b.legend(fontsize=7)
    fig.suptitle(machine_line(), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def bench_scaling(frames):
    rows = []
    scenes = ["bunny_res4.glb", "bunny_res3.glb", "bunny_res2.glb", "bunny.glb"]
    sizes = [(320, 240), (640, 480), (1280, 960), (1920, 1080)]
    for name in scenes:
        for w, h in sizes:
            s = run([os.path.join(MODELS, name), "--width", str(w), "--height", str(h),
                     "--primary-only"], frames)
            rows.append(row(f"{name} {w}x{h}", s, scene=name, kind="size",
                            ns_per_ray=s["frame_ms"] * 1e6 / s["rays"]["total"]))
            print(f"scaling {name:15s} {w}x{h}: {s['frame_ms']:8.2f} ms, "
                  f"{s['mrays_per_s']:6.2f} Mrays/s, build {s['build_ms']:.1f} ms", flush=True)
    return rows + thread_rows(frames)


# The passes of a Whitted frame by which the thread scaling is charted: gridrt's own
# (host passes, the PE kernels, phase 2) and those every tracer shares (shading, frame).
GRIDRT_PASSES = ("walk_ms", "binning_ms", "bundling_ms", "kernel_ms", "reduce_ms", "shade_ms",
                 "frame_ms")


def embree_passes():
    return WHITTED_PHASES + ("frame_ms",)


def thread_counts():
    """1, 2, 4, ... up to the machine's cores, and the cores themselves."""
    cores = os.cpu_count() or 1
    counts = [1]
    while counts[-1] * 2 <= cores:
        counts.append(counts[-1] * 2)
    return counts if counts[-1] == cores else counts + [cores]


def thread_rows(frames, rounds=None):
    """The default Whitted frame on 1..cores threads (gridrt's --threads: host loops and a CPU
    device; Embree packets in the same renderer on as many), the variants in turns, each
    pass the median of the rounds; the speed-up of each against its own 1-thread time."""
    rounds = rounds or TARGET_RUNS
    args = ["--width", "640", "--height", "480", "--max-depth", "5"]
    variants = []
    for t in thread_counts():
        variants.append((("gridrt", t), lambda t=t: run(args + ["--threads", str(t)], frames)))
        if os.path.exists(EMBREE_PEER):
            variants.append((("embree 16-ray packets", t),
                             lambda t=t: run_peer_whitted(args, frames, 16, threads=t)))
    results = {key: [] for key, _ in variants}
    for _ in range(rounds):
        for key, measure in variants:
            results[key].append(measure())
    rows = []
    for (tracer, t), _ in variants:
        passes = GRIDRT_PASSES if tracer == "gridrt" else embree_passes()
        s = medians(results[(tracer, t)], passes)
        rows.append({"label": f"default scene {t} threads [{tracer}]", "kind": "threads",
                     "variant": tracer, "threads": t, **{k: s[k] for k in passes}})
    for r in rows:
        one = next(x for x in rows if x["variant"] == r["variant"] and x["threads"] == 1)
        for k in GRIDRT_PASSES + embree_passes():
            if k in r and r[k] > 0:
                r[f"speedup_{k}"] = one[k] / r[k]
        shown = ", ".join(f"{k[:-3]} {r[k]:.2f} ({r[f'speedup_{k}']:.2f}x)"
                          for k in (GRIDRT_PASSES if r["variant"] == "gridrt" else embree_passes())
                          if f"speedup_{k}" in r)
        print(f"threads {r['threads']:3d} [{r['variant']:21s}]: {shown}", flush=True)
    return rows


def chart_scaling(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    threads = [r for r in rows if r.get("kind") == "threads"]
    rows = [r for r in rows if r.get("kind") != "threads"]
    fig, axes = plt.subplots(1, 4, figsize=(20, 4.5))
    sizes = sorted({(r["width"], r["height"]) for r in rows})
    for w, h in sizes:
        pts = sorted((r["triangles"], r["ns_per_ray"]) for r in rows if r["width"] == w)
        axes[0].plot(*zip(*pts), marker="o", label=f"{w}x{h}")
    axes[0].set(xscale="log", yscale="log", xlabel="triangles", ylabel="ns per ray",
                title="time per ray vs triangles")
    for scene in sorted({r["scene"] for r in rows}, key=lambda n: min(r["triangles"] for r in rows if r["scene"] == n)):
        pts = sorted((r["rays"], r["ns_per_ray"]) for r in rows if r["scene"] == scene)
        axes[1].plot(*zip(*pts), marker="o", label=scene)
    axes[1].set(xscale="log", yscale="log", xlabel="rays per frame", ylabel="ns per ray",
                title="time per ray vs rays")
    per_scene = {}
    for r in rows:
        per_scene.setdefault(r["triangles"], []).append(r)
    tris = sorted(per_scene)
    axes[2].plot(tris, [min(x["build_ms"] for x in per_scene[t]) for t in tris], marker="o", label="grid build")
    big = max(sizes)
    axes[2].plot(tris, [next(x["lists_ms"] for x in per_scene[t] if (x["width"], x["height"]) == big) for t in tris],
                 marker="s", label=f"traversal lists ({big[0]}x{big[1]})")
    axes[2].set(xscale="log", yscale="log", xlabel="triangles", ylabel="ms",
                title="grid build and list generation")
    counts = sorted({r["threads"] for r in threads})
    names = {"walk_ms": "list walk", "binning_ms": "binning", "bundling_ms": "bundling",
             "kernel_ms": "PE kernels", "reduce_ms": "phase 2", "shade_ms": "shading",
             "frame_ms": "frame", "trace_primary_ms": "camera rays",
             "trace_secondary_ms": "reflection+refraction", "trace_shadow_ms": "shadow rays"}
    for tracer, style in (("gridrt", "-"), ("embree 16-ray packets", ":")):
        mine = sorted((r for r in threads if r["variant"] == tracer), key=lambda r: r["threads"])
        passes = GRIDRT_PASSES if tracer == "gridrt" else embree_passes()
        for k in passes:
            if mine and all(f"speedup_{k}" in r for r in mine):
                axes[3].plot([r["threads"] for r in mine], [r[f"speedup_{k}"] for r in mine],
                             style, marker="o", label=f"{tracer}: {names.get(k, k)}",
                             color=plt.cm.tab10(list(names).index(k) % 10),
                             linewidth=2.5 if k == "frame_ms" else 1)
    if counts:
        axes[3].plot(counts, counts, color="grey", linewidth=0.5, label="ideal")
    axes[3].set(xlabel="threads", ylabel="speed-up over 1 thread",
                title="default Whitted frame: each pass against threads")
    for a in axes:
        a.legend(fontsize=6)
    fig.suptitle(machine_line(), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# Wave sizes of bench.py waves: one wave for the whole 640x480 frame down to 1/32 of it.
WAVE_SIZES = (524288, 153600, 76800, 38400, 19200, 9600)


def bench_waves(frames, rounds=None):
    """The default Whitted frame and the bunny's (640x480, depth 5) at each --wave-rays, the
    sizes in turns, each pass the median of the rounds (the images are the same bits)."""
    rounds = rounds or TARGET_RUNS
    rows = []
    for label, scene in [("default scene", []), ("bunny", [os.path.join(MODELS, "bunny.glb")])]:
        args = scene + ["--width", "640", "--height", "480", "--max-depth", "5"]
        results = {w: [] for w in WAVE_SIZES}
        for _ in range(rounds):
            for w in WAVE_SIZES:
                results[w].append(run(args + ["--wave-rays", str(w)], frames))
        for w in WAVE_SIZES:
            s = medians(results[w], GRIDRT_PASSES + ("lists_ms",))
            rows.append({"label": f"{label} waves of {w}", "scene": label, "wave_rays": w,
                         "waves": s["passes"], **{k: s[k] for k in GRIDRT_PASSES}})
            print(f"waves {label:13s} {w:7d} rays ({s['passes']} waves): " +
                  ", ".join(f"{k[:-3]} {s[k]:.2f}" for k in GRIDRT_PASSES), flush=True)
    return rows


def chart_waves(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(6 * len(scenes), 4.5), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        mine = sorted((r for r in rows if r["scene"] == scene), key=lambda r: r["wave_rays"])
        for k in GRIDRT_PASSES:
            ax.plot([r["wave_rays"] for r in mine], [r[k] for r in mine], marker="o",
                    label=k.replace("_ms", ""), linewidth=2.5 if k == "frame_ms" else 1)
        ax.set(xscale="log", xlabel="camera rays a wave (--wave-rays)", ylabel="ms a frame",
               title=f"{scene}: the frame by pass against its wave size")
        ax.legend(fontsize=7)
    fig.suptitle(machine_line(), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def medians(results, keys):
    """The first process's statistics with `keys` replaced by their medians over all."""
    s = dict(results[0])
    for key in keys:
        s[key] = statistics.median(r[key] for r in results)
    return s


def run_with_fps(args, frames):
    """run(), with the frame rate added."""
    r = run(args, frames)
    r["fps"] = 1000.0 / r["frame_ms"]
    return r


def run_median(args, frames, runs):
    """run() in `runs` separate processes; frame and phase times are their medians (one
    busy minute on a shared machine moves a single process by a third)."""
    return medians([run_with_fps(args, frames) for _ in range(runs)], MEDIAN_KEYS)


# The tracing time by ray kind (stats "trace"): milliseconds a frame and nanoseconds a ray.
RAY_KINDS = ("primary", "secondary", "shadow")
TRACE_KEYS = tuple(f"trace_{kind}_{unit}" for kind in RAY_KINDS for unit in ("ms", "ns_per_ray"))
# The statistics run_median() takes the median of.
MEDIAN_KEYS = ("frame_ms", "fps", "lists_ms", "kernel_ms", "kernel_device_ms",
               "transfer_device_ms", "reduce_ms", "shade_ms", "build_ms",
               "mrays_per_s") + LIST_PASSES + TRACE_KEYS


def run_peer_whitted(args, frames, packet, threads=2):
    """embree_peer --whitted: gridrt's renderer with Embree tracing, its figures under the
    names gridrt's statistics use (trace_primary_ms, ...)."""
    s = run_peer(args + ["--whitted"], frames, packet, threads=threads)
    for key, value in s.get("trace", {}).items():
        s["trace_" + key] = value
    return s


# The phases of a Whitted frame any intersector has: tracing by ray kind, then shading.
WHITTED_PHASES = tuple(f"trace_{kind}_ms" for kind in RAY_KINDS) + ("shade_ms",)


def bench_whitted(frames):
    rows = []
    for label, scene in [("default scene", []), ("bunny_res4", [os.path.join(MODELS, "bunny_res4.glb")]),
                         ("bunny", [os.path.join(MODELS, "bunny.glb")])]:
        s = run_median(scene + ["--width", "640", "--height", "480", "--max-depth", "5"], frames,
                       TARGET_RUNS)
        rows.append(row(label, s, fps=s["fps"], **{k: s[k] for k in TRACE_KEYS}))
        per_ray = ", ".join(f"{kind} {s[f'trace_{kind}_ns_per_ray']:.0f}" for kind in RAY_KINDS)
        print(f"whitted {label:14s}: {s['frame_ms']:8.2f} ms = {s['fps']:6.1f} fps, "
              f"{s['rays']['total']} rays; ns a ray traced: {per_ray}", flush=True)
    return rows + whitted_peer_rows(frames)


# The scenes of the three-way comparison: (label, scene arguments, whether each image is also
# measured against the exact reference, which brute force makes too slow for the full bunny).
WHITTED_PEER_SCENES = [("default scene", [], True),
                       ("bunny", [os.path.join(MODELS, "bunny.glb")], False)]


def whitted_peer_rows(frames):
    """Each scene's frame in the same renderer with gridrt and with Embree tracing, the
    variants in turns, TARGET_RUNS rounds: by phase, each the median of the rounds."""
    if not os.path.exists(EMBREE_PEER):
        print(f"no {EMBREE_PEER} (tools/setup.sh --bench builds it): Embree left out")
        return []
    rows = []
    for scene, scene_args, check_accuracy in WHITTED_PEER_SCENES:
        args = scene_args + ["--width", "640", "--height", "480", "--max-depth", "5"]
        variants = [("gridrt", lambda args=args: run_with_fps(args, frames))]
        variants += [(name, lambda packet=packet, args=args: run_peer_whitted(args, frames, packet))
                     for name, packet in EMBREE_VARIANTS]
        results = {name: [] for name, _ in variants}
        for _ in range(TARGET_RUNS):
            for name, measure in variants:
                results[name].append(measure())
        off = whitted_pixels_off_reference(args) if check_accuracy else {}
        for name, _ in variants:
            s = medians(results[name], ("frame_ms", "fps") + WHITTED_PHASES)
            rows.append({"label": f"{scene} [{name}]", "scene": scene, "variant": name,
                         "peer_comparison": 1, "frame_ms": s["frame_ms"], "fps": s["fps"],
                         **{k: s[k] for k in WHITTED_PHASES},
                         "pixels_off_reference": off.get(name, "")})
            phases = ", ".join(f"{k.replace('trace_', '').replace('_ms', '')} {s[k]:.1f}"
                               for k in WHITTED_PHASES)
            accuracy = (f"; {off[name]} pixels off the reference by > {WHITTED_TOLERANCE}"
                        if name in off else "")
            print(f"whitted {scene} [{name:21s}]: {s['frame_ms']:8.2f} ms = {s['fps']:6.1f} fps; "
                  f"ms: {phases}{accuracy}", flush=True)
    return rows


# A pixel of a Whitted image is off the reference when a channel differs by more than this
# (linear radiance): well above float rounding, well below a wrong surface's colour.
WHITTED_TOLERANCE = 0.1


def whitted_pixels_off_reference(args):
    """Per variant (gridrt, Embree 1-ray, Embree packets), the pixels of one Whitted image
    that differ from the exact reference's (gridrt --accel reference) by more than
    WHITTED_TOLERANCE in a channel."""
    import numpy as np
    import OpenImageIO as oiio
    read = lambda p: np.asarray(oiio.ImageBuf(p).get_pixels(oiio.FLOAT))[..., :3]
    with tempfile.TemporaryDirectory() as tmp:
        image = lambda name: os.path.join(tmp, name.replace(" ", "_") + ".exr")
        for name, extra in [("reference", ["--accel", "reference"]), ("gridrt", [])]:
            subprocess.run([GRIDRT, *args, *extra, "-q", "-o", image(name)], check=True)
        for name, packet in EMBREE_VARIANTS:
            run_peer(args + ["--whitted"], 1, packet, ["-o", image(name)])
        want = read(image("reference"))
        return {name: int((np.abs(read(image(name)) - want).max(axis=-1) > WHITTED_TOLERANCE).sum())
                for name in ["gridrt"] + [v for v, _ in EMBREE_VARIANTS]}


def grouped_bars(ax, groups, series):
    """One bar per (label, values) series in each group, side by side, centred on the
    group's tick."""
    width = 0.8 / max(1, len(series))
    for k, (label, values) in enumerate(series):
        offset = (k - (len(series) - 1) / 2) * width
        ax.bar([i + offset for i in range(len(groups))], values, width, label=label)
    ax.set_xticks(range(len(groups)), groups)


# The default scene's frame by phase in the same renderer, gridrt and both Embree modes, as
# bench.py whitted first measured it on the Zen 4 machine (2026-12-01, commit 3b9437e: the
# peer rows of that run's whitted.csv): the "before" the chart's last panel sets this run
# beside.
WHITTED_BEFORE = os.path.join(ROOT, "bench", "whitted_before.csv")


def read_whitted_before():
    if not os.path.exists(WHITTED_BEFORE):
        return []
    with open(WHITTED_BEFORE, newline="") as f:
        return [{k: (v if k in ("scene", "variant", "date", "commit") else float(v))
                 for k, v in r.items()} for r in csv.DictReader(f)]


def peer_scene(row):
    """The scene of a three-way comparison row (older CSVs name none: the default scene)."""
    return row.get("scene") or "default scene"


def stack_whitted_phases(ax, at, rows, labels):
    """Each row's frame by phase (WHITTED_PHASES) as one stacked bar at `at`, its whole frame
    as a dot, and the 30 fps line."""
    bottom = [0.0] * len(rows)
    for p in WHITTED_PHASES:
        vals = [float(r[p]) for r in rows]
        ax.bar(at, vals, bottom=bottom, label=p.replace("trace_", "trace ").replace("_ms", ""))
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax.scatter(at, [float(r["frame_ms"]) for r in rows], color="k", zorder=5, label="frame")
    ax.axhline(1000.0 / 30.0, color="red", ls="--", label="30 fps")
    ax.set_xticks(at, labels)
    ax.set_ylabel("ms per frame")
    ax.legend(fontsize=7, ncol=3, loc="upper right")


def chart_before_after(ax, before, peers):
    """Each variant's frame by phase, before (WHITTED_BEFORE) and in this run, side by side."""
    now = {r["variant"]: r for r in peers if peer_scene(r) == before[0]["scene"]}
    pairs = [(b, now[b["variant"]]) for b in before if b["variant"] in now]
    labels, stacks, at = [], [], []
    for k, (b, n) in enumerate(pairs):
        name = b["variant"].replace("16-ray packets", "packets")
        labels += [f"{name}\n{b['date']}", f"{name}\nnow"]
        stacks += [b, n]
        at += [2.5 * k, 2.5 * k + 1]  # a gap between the variants' pairs
    stack_whitted_phases(ax, at, stacks, labels)
    ax.tick_params(axis="x", labelsize=6)
    ax.set_title(f"{before[0]['scene']}: the frame by phase, before and now")
    ax.set_ylim(0, 1.3 * max(float(r["frame_ms"]) for r in stacks))


def chart_whitted(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    peers = [r for r in rows if r.get("peer_comparison")]
    rows = [r for r in rows if not r.get("peer_comparison")]
    # One panel per scene of the three-way comparison (older CSVs name no scene: the default),
    # one of frame time against pixels off the reference where those were measured, and one of
    # the frame by phase before (WHITTED_BEFORE) and now.
    peer_scenes = list(dict.fromkeys(peer_scene(r) for r in peers))
    judged = [r for r in peers if r.get("pixels_off_reference") not in (None, "")]
    before = read_whitted_before() if peers else []
    panels = 2 + len(peer_scenes) + (1 if judged else 0) + (1 if before else 0)
    columns = min(panels, 3)
    rows_of_panels = (panels + columns - 1) // columns
    fig, grid = plt.subplots(rows_of_panels, columns, figsize=(6 * columns, 4.5 * rows_of_panels),
                             squeeze=False)
    axes = list(grid.flat)
    for unused in axes[panels:]:
        unused.axis("off")
    ax, kinds = axes[0], axes[1]
    phases = [*LIST_PASSES, "kernel_ms", "reduce_ms", "shade_ms"]
    bottom = [0.0] * len(rows)
    for p in phases:
        vals = [r[p] for r in rows]
        ax.bar([r["label"] for r in rows], vals, bottom=bottom,
               label=PHASE_NAMES.get(p, p.replace("_ms", "")))
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax.scatter([r["label"] for r in rows], [r["frame_ms"] for r in rows], color="k", zorder=5,
               label="frame")
    ax.set(ylabel="ms per frame (640x480, max depth 5)", title="Whitted frames: time per phase")
    ax.legend(fontsize=8)
    # What one ray of each kind cost to trace (lists, kernel and phase 2 together).
    grouped_bars(kinds, [r["label"] for r in rows],
                 [(kind, [r[f"trace_{kind}_ns_per_ray"] for r in rows]) for kind in RAY_KINDS])
    kinds.set(ylabel="ns per ray traced", title="Tracing cost by ray kind")
    kinds.legend(fontsize=8)
    if judged:
        # Speed against accuracy: each variant's frame and its pixels off the exact reference.
        ax = axes[2]
        for r in judged:
            ax.scatter(r["frame_ms"], float(r["pixels_off_reference"]), s=60, zorder=3)
            ax.annotate(r["variant"], (r["frame_ms"], float(r["pixels_off_reference"])),
                        textcoords="offset points", xytext=(6, 4), fontsize=8)
        ax.axvline(1000.0 / 30.0, color="red", ls="--", label="30 fps")
        ax.set(xlabel="ms per frame", ylabel=f"pixels off the exact reference by > {WHITTED_TOLERANCE}",
               title=f"{peer_scene(judged[0])}: speed against accuracy "
                     f"(of {640 * 480:,} pixels)")
        ax.set_xlim(0, 1.25 * max(r["frame_ms"] for r in judged))
        ax.set_ylim(-5, 1.25 * max(float(r["pixels_off_reference"]) for r in judged) + 5)
        ax.legend(fontsize=7)
    for ax, scene in zip(axes[2 + (1 if judged else 0):], peer_scenes):
        # The frame with each intersector in the same renderer, by phase, and where measured
        # the accuracy beside the speed: each variant's pixels off the exact reference.
        group = [r for r in peers if peer_scene(r) == scene]
        labels = [r["variant"] + (f"\n{r['pixels_off_reference']} px off the reference"
                                  if r.get("pixels_off_reference") not in (None, "") else "")
                  for r in group]
        stack_whitted_phases(ax, range(len(group)), group, labels)
        ax.set_title(f"{scene}: the same renderer, gridrt or Embree tracing")
        ax.set_ylim(0, 1.45 * max(max(r["frame_ms"] for r in group), 1000.0 / 30.0))
        ax.tick_params(axis="x", labelsize=8)
    if before:
        chart_before_after(axes[panels - 1], before, peers)
    fig.suptitle(machine_line(), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# The speed targets and the runs that measure them: each figure is the median,
# over RUNS separate processes, of each process's median frame.
TARGET_RUNS = 5
TARGETS = [
    ("bunny_res4 320x240 primary, ms/frame (<= 2)", "frame_ms",
     [os.path.join(MODELS, "bunny_res4.glb"), "--width", "320", "--height", "240", "--primary-only"]),
    ("bunny 1280x960 primary, Mrays/s (>= 20)", "mrays_per_s",
     [os.path.join(MODELS, "bunny.glb"), "--width", "1280", "--height", "960", "--primary-only"]),
    ("bunny grid build, ms (<= 40)", "build_ms",
     [os.path.join(MODELS, "bunny.glb"), "--width", "64", "--height", "48", "--primary-only"]),
    ("default scene 640x480 Whitted depth 5, fps (>= 30)", "fps",
     ["--width", "640", "--height", "480", "--max-depth", "5"]),
]


# Embree's variants of a target: its single-ray and 16-ray packet paths on both cores.
EMBREE_VARIANTS = [("embree 1-ray", 1), ("embree 16-ray packets", 16)]
# A primary-ray target's Embree variant that renders the frame gridrt renders (camera rays,
# headlight shading) in gridrt's renderer, Embree's packets tracing: the like-for-like
# figure beside the trace-only ones above.
EMBREE_FRAME_VARIANT = "embree packets, whole frame"


def run_peer(args, frames, packet, extra=(), threads=2):
    """embree_peer on a gridrt-style argument list (scene, --width, --height)."""
    out = subprocess.run([EMBREE_PEER, *args, "--threads", str(threads), "--packet", str(packet),
                          "--frames", str(frames), *extra],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def peer_row(label, s, **extra):
    r = {"label": label, "accel": f"embree packet {s['packet']}", "triangles": s["triangles"],
         "rays": s["rays"], "frame_ms": s["frame_ms"], "mrays_per_s": s["mrays_per_s"],
         "build_ms": s["build_ms"]}
    if "fps" in s:  # --whitted: gridrt's renderer with Embree tracing
        r.update(fps=s["fps"], **{k: s[k] for k in WHITTED_PHASES})
    r.update(extra)
    return r


# gridrt's variants of a target.
GRIDRT_VARIANTS = [("gridrt", []), ("gridrt --pe-interrupt", ["--pe-interrupt"]),
                   ("dda", ["--accel", "dda"])]
# The variant every other one is compared with, round by round (the targets' yardstick).
YARDSTICK = "embree 1-ray"


def speedup(key, value, yardstick):
    """How many times faster than the yardstick a value of `key` is (> 1: faster)."""
    return value / yardstick if key in ("mrays_per_s", "fps") else yardstick / value


def goal_of(label):
    """A target label's goal, "(<= 2)" or "(>= 20)" at its end: (comparison, value)."""
    op, value = label.rsplit("(", 1)[1].rstrip(")").split()
    return op, float(value)


def meets(label, value):
    op, goal = goal_of(label)
    return value <= goal if op == "<=" else value >= goal


def bench_targets(frames, rounds=None):
    """Each target's variants run in turns, one process each per round, `rounds` rounds
    (TARGET_RUNS by default): a busy minute then slows every variant alike instead of the
    ones that ran in it. Each figure is the median over the rounds, with the rounds' lowest
    and highest (value_min, value_max) and how many rounds met the target (rounds_met of
    rounds): on a noisy machine a median near the line says less than that count.
    `vs_embree_1ray` is the median over the rounds of the speed-up on Embree's single-ray
    path measured in the same round."""
    rounds = rounds or TARGET_RUNS
    rows = []
    peer = os.path.exists(EMBREE_PEER)
    if not peer:
        print(f"no {EMBREE_PEER} (tools/setup.sh --bench builds it): Embree columns left out")
    for label, key, args in TARGETS:
        variants = [(name, lambda extra=extra: run_with_fps(args + extra, frames))
                    for name, extra in GRIDRT_VARIANTS]
        if peer:  # camera rays alone, or (fps) gridrt's Whitted renderer with Embree tracing
            if key == "fps":
                measure = lambda packet: run_peer_whitted(args, frames, packet)
            else:
                peer_args = [a for a in args if a != "--primary-only"]
                measure = lambda packet: run_peer(peer_args, frames, packet)
            variants += [(name, lambda packet=packet, measure=measure: measure(packet))
                         for name, packet in EMBREE_VARIANTS]
            if "--primary-only" in args and key != "build_ms":
                variants.append((EMBREE_FRAME_VARIANT, lambda: run_peer_whitted(args, frames, 16)))
        results = {name: [] for name, _ in variants}
        for _ in range(rounds):
            for name, measure in variants:
                results[name].append(measure())
        for name, _ in variants:
            embree = name.startswith("embree")
            s = medians(results[name], ("frame_ms", "mrays_per_s", "build_ms") +
                        (("fps",) if key == "fps" else ()) if embree else MEDIAN_KEYS)
            value = s[key]
            per_round = [r[key] for r in results[name]]
            extra = {"value_min": min(per_round), "value_max": max(per_round),
                     "rounds_met": sum(meets(label, v) for v in per_round), "rounds": rounds}
            if YARDSTICK in results:
                extra["vs_embree_1ray"] = statistics.median(
                    speedup(key, mine[key], theirs[key])
                    for mine, theirs in zip(results[name], results[YARDSTICK]))
            r = (peer_row if embree else row)(f"{label} [{name}]", s, target=label, variant=name,
                                              value=value, **extra)
            rows.append(r)
            versus = (f", {extra['vs_embree_1ray']:.2f}x Embree 1-ray"
                      if "vs_embree_1ray" in extra else "")
            what = "trace" if embree and key != "fps" and name != EMBREE_FRAME_VARIANT else "frame"
            print(f"target {label:52s} {name:22s}: {value:8.2f}  (rounds {min(per_round):.2f}-"
                  f"{max(per_round):.2f}, met in {extra['rounds_met']} of {rounds}; {what} "
                  f"{s['frame_ms']:.2f} ms{versus})", flush=True)
    return rows + accuracy_rows(peer)


# The accuracy beside the speed: per scene (320x240 camera rays), the pixels whose
# triangle differs from the exact double-precision host reference (--accel reference),
# and the largest difference in hit distance among them (0: a tie between triangles at
# the same distance, e.g. duplicate faces; larger: a different surface).
ACCURACY_SCENES = ["bunny_res4.glb", "bunny.glb"]
ACCURACY_TARGET = "pixels whose triangle differs from the exact reference (320x240)"


def primary_aovs(tmp, name, runner):
    """(primid, depth) arrays of one renderer, runner(primid_path, depth_path) making them."""
    import numpy as np
    import OpenImageIO as oiio
    pid, depth = os.path.join(tmp, f"{name}_pid.exr"), os.path.join(tmp, f"{name}_depth.exr")
    runner(pid, depth)
    read = lambda p: np.asarray(oiio.ImageBuf(p).get_pixels(oiio.FLOAT))[..., 0]
    return read(pid), read(depth)


def accuracy_rows(peer):
    import numpy as np
    rows = []
    for scene in ACCURACY_SCENES:
        args = [os.path.join(MODELS, scene), "--width", "320", "--height", "240"]

        def gridrt(extra):
            return lambda pid, depth: subprocess.run(
                [GRIDRT, *args, "--primary-only", "-q", "-o", pid + ".png", "--aov",
                 f"primid={pid}", "--aov", f"depth={depth}", *extra], check=True)

        variants = [("gridrt", gridrt([])), ("gridrt --pe-interrupt", gridrt(["--pe-interrupt"])),
                    ("dda", gridrt(["--accel", "dda"]))]
        if peer:
            variants += [(v, lambda pid, depth, packet=packet: run_peer(
                args, 5, packet, ["--primid", pid, "--depth", depth])) for v, packet in EMBREE_VARIANTS]
        with tempfile.TemporaryDirectory() as tmp:
            ref_pid, ref_depth = primary_aovs(tmp, "reference", gridrt(["--accel", "reference"]))
            for variant, runner in variants:
                pid, depth = primary_aovs(tmp, variant.replace(" ", "_"), runner)
                differ = pid != ref_pid
                dt = float(np.abs(depth - ref_depth)[differ].max()) if differ.any() else 0.0
                rows.append({"label": f"{scene} accuracy [{variant}]", "target": ACCURACY_TARGET,
                             "variant": variant, "scene": scene, "value": int(differ.sum()),
                             "max_depth_difference": dt, "pixels": int(differ.size)})
                print(f"accuracy {scene:15s} {variant:22s}: {int(differ.sum()):6d} of "
                      f"{differ.size} pixels differ from the reference (max |dt| {dt:.3g})",
                      flush=True)
    return rows


def chart_targets(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    speed = [r for r in rows if r["target"] != ACCURACY_TARGET]
    accuracy = [r for r in rows if r["target"] == ACCURACY_TARGET]
    targets = list(dict.fromkeys(r["target"] for r in speed))
    fig, axes = plt.subplots(1, len(targets) + 1, figsize=(4 * (len(targets) + 1), 4.4))
    for ax, target in zip(axes, targets):
        sub = [r for r in speed if r["target"] == target]
        values = [r["value"] for r in sub]
        ax.bar([r["variant"] for r in sub], values,
               color=["C1" if r["variant"].startswith("embree") else "C0" for r in sub],
               yerr=[[v - r["value_min"] for v, r in zip(values, sub)],
                     [r["value_max"] - v for v, r in zip(values, sub)]],
               capsize=3, error_kw={"elinewidth": 0.8})
        goal = goal_of(target)[1]
        ax.axhline(goal, color="red", ls="--", label=f"target {goal:g}")
        ax.set_title(target, fontsize=8)
        ax.tick_params(axis="x", labelsize=7, rotation=30)
        ax.legend(fontsize=7)
    ax = axes[-1]
    variants = list(dict.fromkeys(r["variant"] for r in accuracy))
    scenes = list(dict.fromkeys(r["scene"] for r in accuracy))
    series = []
    for scene in scenes:
        values = {r["variant"]: r["value"] for r in accuracy if r["scene"] == scene}
        series.append((scene, [values.get(v, 0) for v in variants]))
    grouped_bars(ax, variants, series)
    ax.tick_params(axis="x", labelsize=7, rotation=30)
    ax.set_title("accuracy: " + ACCURACY_TARGET.replace(" from", "\nfrom"), fontsize=8)
    ax.set_ylabel("pixels (of 76,800)")
    ax.legend(fontsize=7)
    fig.suptitle(machine_line() + "; bars: the median round, whiskers: the lowest and highest"
                 " round; Embree: the camera rays' trace only (no ray generation or shading), but the whole"
                 " frame in gridrt's renderer for 'whole frame' and the Whitted target", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# One render per process, as a user runs it: the whole process's wall time (start-up,
# loading the kernels, the first frame, writing the PNG) and its peak memory.
SINGLE_RUNS = 3
SINGLE = [("default scene", []), ("bunny", [os.path.join(MODELS, "bunny.glb")])]
SINGLE_SIZES = [(640, 480), (1920, 1080), (3840, 2160)]


def run_single(args):
    return gridrt_stats(args)


def bench_single(frames):
    rows = []
    for label, scene in SINGLE:
        for w, h in SINGLE_SIZES:
            results = [run_single(scene + ["--width", str(w), "--height", str(h)])
                       for _ in range(SINGLE_RUNS)]
            s = medians(results, ("wall_s", "peak_mb", "frame_ms"))
            rows.append(row(f"{label} {w}x{h}", s, scene=label, wall_s=s["wall_s"],
                            peak_mb=s["peak_mb"], passes=s.get("passes", 1)))
            print(f"single {label:14s} {w}x{h}: {s['wall_s']:6.2f} s, first frame "
                  f"{s['frame_ms']:8.1f} ms, peak {s['peak_mb']:7.0f} MB", flush=True)
    return rows


def chart_single(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for k, scene in enumerate(dict.fromkeys(r["scene"] for r in rows)):
        sub = [r for r in rows if r["scene"] == scene]
        pixels = [r["width"] * r["height"] / 1e6 for r in sub]
        colour = f"C{k}"
        axes[0].plot(pixels, [r["wall_s"] for r in sub], "o-", color=colour,
                     label=f"{scene}: whole process")
        axes[0].plot(pixels, [r["frame_ms"] / 1000 for r in sub], "x--", color=colour,
                     label=f"{scene}: its frame")
        axes[1].plot(pixels, [r["peak_mb"] for r in sub], "o-", color=colour, label=scene)
    axes[0].set(xlabel="megapixels", ylabel="seconds", title="One render (Whitted, depth 5)")
    axes[1].set(xlabel="megapixels", ylabel="peak resident MB", title="Peak memory")
    for a in axes:
        a.legend(fontsize=7)
    fig.suptitle(machine_line().replace("medians of frames after a warm-up",
                                        f"medians of {SINGLE_RUNS} processes"), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def machine_line():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{cpu}, {os.cpu_count()} cores, {opencl_device()}; medians of frames after a warm-up"


def opencl_device():
    """The OpenCL device gridrt renders on by default (the first of --list-devices)."""
    try:
        table = subprocess.run([GRIDRT, "--list-devices"], capture_output=True, text=True,
                               check=True).stdout.splitlines()
        # "0:0   CPU    pthread-skylake-avx512-AMD EPYC   2 ...": type and name
        fields = table[1].split()
        return f"OpenCL {fields[1]} device {' '.join(fields[2:-4])}"
    except (OSError, subprocess.CalledProcessError, IndexError):
        return "OpenCL device unknown"


# The adaptive set: the uneven family (tools/make_uneven_scenes, made from the full bunny
# into build/uneven_scenes when the set runs) and the even scenes, primary rays, with the
# uniform auto grid, the adaptive structure, Embree single-ray and Embree 16-ray packets
# in turns, `rounds` rounds; each figure the median over the rounds. gridrt's figure is its
# primary-ray tracing (trace.primary_ms: bundling, kernels, phase 2), Embree's its trace of
# the same camera rays.
MAKE_UNEVEN = os.path.join(ROOT, "build", "tools", "make_uneven_scenes")
UNEVEN_DIR = os.path.join(ROOT, "build", "uneven_scenes")
UNEVEN_SCENES = ["floor_1x", "floor_10x", "floor_100x", "floor_1000x", "scattered", "row",
                 "huge_triangle"]
ADAPTIVE_EVEN = [("bunny", os.path.join(MODELS, "bunny.glb")),
                 ("bunny_res4", os.path.join(MODELS, "bunny_res4.glb")),
                 ("teapot", os.path.join(MODELS, "teapot.glb")),
                 ("default scene", None)]
ADAPTIVE_SIZES = [(640, 480), (1280, 960)]
ADAPTIVE_VARIANTS = ["uniform", "adaptive", "embree 1-ray", "embree 16-ray packets"]


def adaptive_scenes():
    subprocess.run([MAKE_UNEVEN, os.path.join(MODELS, "bunny.glb"), UNEVEN_DIR], check=True,
                   capture_output=True)
    return [(n, os.path.join(UNEVEN_DIR, n + ".glb")) for n in UNEVEN_SCENES] + ADAPTIVE_EVEN


def bench_adaptive(frames, rounds=None):
    rounds = rounds or TARGET_RUNS
    peer = os.path.exists(EMBREE_PEER)
    if not peer:
        print(f"no {EMBREE_PEER} (tools/setup.sh --bench builds it): Embree columns left out")
    rows = []
    for name, path in adaptive_scenes():
        for w, h in ADAPTIVE_SIZES:
            args = ([path] if path else []) + ["--width", str(w), "--height", str(h)]
            results = {v: [] for v in ADAPTIVE_VARIANTS}
            for _ in range(rounds):
                for grid in ("uniform", "adaptive"):
                    s = run(args + ["--primary-only", "--grid", grid], frames)
                    s["trace_ms"] = s["trace_primary_ms"]
                    results[grid].append(s)
                if peer and path:
                    for label, packet in EMBREE_VARIANTS:
                        s = run_peer(args, frames, packet)
                        s["trace_ms"] = s["frame_ms"]
                        results[label].append(s)
            for variant, runs in results.items():
                if not runs:
                    continue
                ms = statistics.median(r["trace_ms"] for r in runs)
                first = runs[0]
                grid = first.get("grid", {})
                r = {"scene": name, "width": w, "height": h, "variant": variant,
                     "triangles": first["triangles"], "rays": w * h, "trace_ms": ms,
                     "trace_ms_min": min(x["trace_ms"] for x in runs),
                     "trace_ms_max": max(x["trace_ms"] for x in runs), "rounds": len(runs),
                     "mrays_per_s": w * h / (ms * 1e3), "ns_per_ray": ms * 1e6 / (w * h),
                     "build_ms": statistics.median(x["build_ms"] for x in runs)}
                if grid:
                    r.update(pes=grid["pes"], depth=grid.get("depth", 0),
                             grid_memory_mb=grid["memory_bytes"] / 1e6,
                             peak_host_mib=first.get("memory", {}).get("peak_host_mib"))
                rows.append(r)
            base = {r["variant"]: r["trace_ms"] for r in rows
                    if r["scene"] == name and r["width"] == w}
            for r in rows:
                if r["scene"] == name and r["width"] == w:
                    if "embree 1-ray" in base:
                        r["vs_embree_1ray"] = r["trace_ms"] / base["embree 1-ray"]
                    if "embree 16-ray packets" in base:
                        r["vs_embree_packets"] = r["trace_ms"] / base["embree 16-ray packets"]
                    r["vs_uniform"] = r["trace_ms"] / base["uniform"]
            print(f"adaptive {name:14s} {w}x{h}: " + ", ".join(
                f"{v} {ms:.1f} ms" for v, ms in base.items()) + (
                f"; adaptive/embree 1-ray {base['adaptive'] / base['embree 1-ray']:.2f}"
                if "embree 1-ray" in base else ""), flush=True)
    return rows


def chart_adaptive(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(17, 5))
    w0, h0 = ADAPTIVE_SIZES[0]
    small = [r for r in rows if r["width"] == w0]
    scenes = list(dict.fromkeys(r["scene"] for r in small))
    series = []
    for v in ADAPTIVE_VARIANTS:
        values = [next((r["ns_per_ray"] for r in small if r["scene"] == s and r["variant"] == v),
                       float("nan")) for s in scenes]
        series.append((v, values))
    grouped_bars(axes[0], scenes, series)
    axes[0].set(yscale="log", ylabel="ns per primary ray", title=f"primary rays, {w0}x{h0}")
    axes[0].tick_params(axis="x", rotation=45)
    floors = [("floor_1x", 1), ("floor_10x", 10), ("floor_100x", 100), ("floor_1000x", 1000)]
    for v in ADAPTIVE_VARIANTS:
        for w, h in ADAPTIVE_SIZES:
            pts = [(scale, r["ns_per_ray"]) for name, scale in floors for r in rows
                   if r["scene"] == name and r["variant"] == v and r["width"] == w]
            if pts:
                axes[1].plot(*zip(*pts), marker="o", ls="-" if w == w0 else "--",
                             label=f"{v} {w}x{h}")
    axes[1].set(xscale="log", yscale="log", xlabel="floor size / model size",
                ylabel="ns per primary ray", title="the bunny on a floor")
    for v in ADAPTIVE_VARIANTS:
        pts = sorted({(r["triangles"], r["build_ms"]) for r in small if r["variant"] == v})
        if pts:
            axes[2].plot(*zip(*pts), marker="o", ls="none", label=v)
    axes[2].set(xscale="log", yscale="log", xlabel="triangles", ylabel="build ms",
                title="structure build")
    for a in axes:
        a.legend(fontsize=7)
    fig.suptitle(machine_line().replace("medians of frames after a warm-up",
                                        "medians of rounds in turns, frames after a warm-up"),
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# The dynamic set: scenes that move (tools/make_dynamic_scenes.py, made into
# build/dynamic_scenes when the set runs): the full bunny turning (rigid, through a node)
# and sheets of 1k to 400k triangles whose every vertex moves (a morph target), DYNAMIC_FRAMES
# frames at 24 fps each posed, rebuilt and rendered (DYNAMIC_MODES): gridrt --frames
# (its grid rebuilt per frame) and Embree rebuilding its BVH per frame in the same renderer
# (embree_peer --sequence), in turns, `rounds` rounds. Each figure is the median over the
# frames after the first (which loads the file and builds the kernels) and the rounds.
MAKE_DYNAMIC = os.path.join(ROOT, "tools", "make_dynamic_scenes.py")
DYNAMIC_DIR = os.path.join(ROOT, "build", "dynamic_scenes")
DYNAMIC_WAVES = [1000, 10000, 100000, 400000]
DYNAMIC_FRAMES = 12
# Whole Whitted frames, where tracing dominates, and primary rays at a small size, where
# the rebuild does.
DYNAMIC_MODES = [("whitted 640x480", 640, 480, []),
                 ("primary 320x240", 320, 240, ["--primary-only"])]


def dynamic_gridrt(path, w, h, extra):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        subprocess.run([GRIDRT, path, "--frames", f"0:{DYNAMIC_FRAMES - 1}", "--fps", "24",
                        "--width", str(w), "--height", str(h), "-q", *extra,
                        "-o", os.path.join(tmp, "f_%04d.exr"), "--stats-json", stats], check=True)
        with open(stats) as f:
            s = json.load(f)
    return [{"pose_ms": f["pose_ms"], "build_ms": f["build_ms"], "setup_ms": f["setup_ms"],
             "render_ms": f["frame_ms"], "total_ms": f["wall_ms"], "triangles": f["triangles"]}
            for f in s["frames"][1:]]


def dynamic_embree(path, w, h, packet, extra):
    out = subprocess.run([EMBREE_PEER, path, "--whitted", "--sequence",
                          f"0:{DYNAMIC_FRAMES - 1}", "--fps", "24", "--width", str(w),
                          "--height", str(h), "--threads", "2", "--packet", str(packet), *extra],
                         check=True, capture_output=True, text=True).stdout
    return [{"pose_ms": f["pose_ms"], "build_ms": f["build_ms"], "setup_ms": 0.0,
             "render_ms": f["frame_ms"], "total_ms": f["wall_ms"], "triangles": f["triangles"]}
            for f in json.loads(out)["frames"][1:]]


def bench_dynamic(frames, rounds=None):
    rounds = rounds or TARGET_RUNS
    subprocess.run([sys.executable, MAKE_DYNAMIC, DYNAMIC_DIR, "--sizes",
                    ",".join(map(str, DYNAMIC_WAVES))], check=True, capture_output=True)
    scenes = [("bunny_spin", os.path.join(DYNAMIC_DIR, "bunny_spin.glb"))] + [
        (f"wave_{n}", os.path.join(DYNAMIC_DIR, f"wave_{n}.glb")) for n in DYNAMIC_WAVES]
    peer = os.path.exists(EMBREE_PEER)
    if not peer:
        print(f"no {EMBREE_PEER} (tools/setup.sh --bench builds it): Embree columns left out")
    rows = []
    for mode, w, h, extra in DYNAMIC_MODES:
        for name, path in scenes:
            results = {"gridrt": []}
            if peer:
                results.update({label: [] for label, _ in EMBREE_VARIANTS})
            for _ in range(rounds):
                results["gridrt"] += dynamic_gridrt(path, w, h, extra)
                if peer:
                    for label, packet in EMBREE_VARIANTS:
                        results[label] += dynamic_embree(path, w, h, packet, extra)
            base = {}
            for variant, runs in results.items():
                r = {"mode": mode, "scene": name, "variant": variant,
                     "moving_triangles": runs[0]["triangles"], "width": w, "height": h,
                     "frames": len(runs)}
                for key in ("pose_ms", "build_ms", "setup_ms", "render_ms", "total_ms"):
                    r[key] = statistics.median(x[key] for x in runs)
                r["build_share"] = r["build_ms"] / r["total_ms"]
                rows.append(r)
                base[variant] = r
            for r in base.values():
                for label, _ in EMBREE_VARIANTS:
                    if label in base:
                        r["vs_" + label.replace(" ", "_")] = r["total_ms"] / base[label]["total_ms"]
            print(f"dynamic {mode} {name:12s}: " + ", ".join(
                f"{v} {r['total_ms']:.1f} ms/frame (build {r['build_ms']:.1f})"
                for v, r in base.items()), flush=True)
    return rows


def chart_dynamic(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    modes = list(dict.fromkeys(r["mode"] for r in rows))
    fig, axes = plt.subplots(1, len(modes) + 1, figsize=(6 * (len(modes) + 1), 4.5))
    colours = {}
    for ax, mode in zip(axes, modes):
        waves = [r for r in rows if r["mode"] == mode and r["scene"].startswith("wave_")]
        for variant in dict.fromkeys(r["variant"] for r in waves):
            pts = sorted((r["moving_triangles"], r["total_ms"], r["build_ms"]) for r in waves
                         if r["variant"] == variant)
            line = ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o",
                           label=f"{variant}: frame")[0]
            colours[variant] = line.get_color()
            ax.plot([p[0] for p in pts], [p[2] for p in pts], marker="x", ls="--",
                    color=line.get_color(), label=f"{variant}: rebuild")
        ax.set(xscale="log", yscale="log", xlabel="moving triangles (every vertex, every frame)",
               ylabel="ms per frame", title=f"wave sheets, {mode}")
        ax.legend(fontsize=7)
    spin = [r for r in rows if r["scene"] == "bunny_spin"]
    labels = [f"{r['variant']}\n{r['mode']}" for r in spin]
    axes[-1].bar(labels, [r["total_ms"] - r["build_ms"] for r in spin],
                 color=[colours.get(r["variant"]) for r in spin], label="the rest of the frame")
    axes[-1].bar(labels, [r["build_ms"] for r in spin],
                 bottom=[r["total_ms"] - r["build_ms"] for r in spin],
                 color=[colours.get(r["variant"]) for r in spin], alpha=0.4, label="rebuild")
    axes[-1].set(ylabel="ms per frame", title="the full bunny turning (light: rebuild)")
    axes[-1].tick_params(axis="x", labelsize=6, rotation=45)
    fig.suptitle(machine_line().replace("medians of frames after a warm-up",
                                        "medians of frames 1.. of each sequence, rounds in turns"),
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


SETS = {"paper": (bench_paper, chart_paper), "scaling": (bench_scaling, chart_scaling),
        "whitted": (bench_whitted, chart_whitted), "targets": (bench_targets, chart_targets),
        "single": (bench_single, chart_single), "adaptive": (bench_adaptive, chart_adaptive),
        "dynamic": (bench_dynamic, chart_dynamic), "waves": (bench_waves, chart_waves),
        "farm": (bench_farm, chart_farm), "packets": (bench_packets, chart_packets)}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("set", choices=list(SETS) + ["all"])
    p.add_argument("--frames", type=int, default=7, help="timed frames per figure (median), >= 5")
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "results"))
    p.add_argument("--rounds", type=int, default=TARGET_RUNS,
                   help=f"targets, adaptive, dynamic, farm, waves, packets: rounds of every variant in turns (default {TARGET_RUNS}), >= 3")
    a = p.parse_args()
    if a.frames < 5:
        p.error("--frames must be at least 5")
    if a.rounds < 3:
        p.error("--rounds must be at least 3")
    os.makedirs(a.out, exist_ok=True)
    for name in (SETS if a.set == "all" else [a.set]):
        bench, chart = SETS[name]
        rounds_sets = ("targets", "adaptive", "dynamic", "farm", "waves", "packets")
        rows = bench(a.frames, a.rounds) if name in rounds_sets else bench(a.frames)
        write_csv(os.path.join(a.out, f"{name}.csv"), rows)
        chart(rows, os.path.join(a.out, f"{name}.png"))
        print(f"wrote {a.out}/{name}.csv and {name}.png")


if __name__ == "__main__":
    sys.exit(main())
