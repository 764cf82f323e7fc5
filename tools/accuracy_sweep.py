#!/usr/bin/env python3
"""Accuracy sweep: renders scenes with gridrt under several settings, compares each
render with the exact reference (--accel reference: host, double precision) using
tools/compare_renders.py, and writes

  bench/results/accuracy.csv            one row per render
  bench/results/accuracy_time_error.png (a) frame time against RMSE, Pareto front marked
  bench/results/accuracy_scale.png      (b) RMSE against scene scale, per --ray-offset

Settings: intersector (mt / watertight, when gridrt has --intersector) x grid density x
spp for chart (a); scene scale 1e-4 .. 1e4 (a scaled copy of the glTF: a new root node
with that scale, point/spot intensities times scale^2 so the image stays the same) x
ray offset (epsilon=1e-4 / robust) for chart (b). Run with .venv/bin/python."""
import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402  (write_csv)
import compare_renders  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def default_binary():
    for b in ("build-acc/gridrt", "build/gridrt"):
        if os.path.exists(os.path.join(ROOT, b)):
            return os.path.join(ROOT, b)
    return os.path.join(ROOT, "build/gridrt")


def has_flag(binary, flag):
    out = subprocess.run([binary, "--help"], capture_output=True, text=True).stdout
    return flag in out


def render(binary, scene, out_dir, tag, args, size):
    """Runs gridrt; returns (image path, primid path, stats dict)."""
    img = os.path.join(out_dir, f"{tag}.exr")
    pid = os.path.join(out_dir, f"{tag}_primid.exr")
    stats = os.path.join(out_dir, f"{tag}.json")
    cmd = [binary] + ([scene] if scene else []) + [
        "-q", "-o", img, "--width", str(size[0]), "--height", str(size[1]),
        "--aov", f"primid={pid}", "--stats-json", stats] + args
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()}")
    with open(stats) as f:
        return img, pid, json.load(f)


def scaled_copy(scene, scale, out_dir):
    """A copy of a .gltf scene under a new root node scaled by `scale`."""
    with open(scene) as f:
        doc = json.load(f)
    base = os.path.dirname(os.path.abspath(scene))
    for b in doc.get("buffers", []):  # external buffers travel with the copy
        uri = b.get("uri", "")
        if uri and not uri.startswith("data:"):
            shutil.copy(os.path.join(base, uri), os.path.join(out_dir, os.path.basename(uri)))
            b["uri"] = os.path.basename(uri)
    nodes = doc.setdefault("nodes", [])
    s = doc.get("scene", 0)
    scenes = doc.setdefault("scenes", [{"nodes": list(range(len(nodes)))}])
    nodes.append({"name": "accuracy_sweep_scale", "scale": [scale] * 3,
                  "children": scenes[s]["nodes"]})
    scenes[s]["nodes"] = [len(nodes) - 1]
    for light in doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []):
        if light.get("type") in ("point", "spot"):
            light["intensity"] = light.get("intensity", 1.0) * scale * scale
            if "range" in light:
                light["range"] *= scale
    path = os.path.join(out_dir, f"scaled_{scale:g}.gltf")
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def pareto(points):
    """Indices of the points no other point beats in both time and error."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for t2, e2 in points):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def main(argv=None):
    p = argparse.ArgumentParser(description="GridRT accuracy sweep")
    p.add_argument("--binary", default=default_binary())
    p.add_argument("--scenes", nargs="*", default=[os.path.join(ROOT, "scenes/default.gltf")])
    p.add_argument("--scale-scene", default=os.path.join(ROOT, "scenes/default.gltf"))
    p.add_argument("--densities", nargs="*", type=float, default=[0.1, 0.25, 0.5, 1, 4])
    p.add_argument("--spp", nargs="*", type=int, default=[1, 4])
    p.add_argument("--scales", nargs="*", type=float, default=[1e-4, 1e-2, 1, 1e2, 1e4])
    p.add_argument("--size", default="160x120")
    p.add_argument("--repeat", type=int, default=2, help="extra frames timed per render")
    p.add_argument("--out", default=os.path.join(ROOT, "bench/results"))
    args = p.parse_args(argv)
    size = tuple(int(x) for x in args.size.split("x"))
    os.makedirs(args.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="gridrt_accuracy_")
    intersectors = ["mt", "watertight"] if has_flag(args.binary, "--intersector") else [None]
    rows = []

    def compare(img, pid, ref, display=False):
        r = compare_renders.image_error(img, ref[0], display)
        r.update(compare_renders.primid_difference(pid, ref[1]))
        return r

    # (a) time against error.
    for scene in args.scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        for spp in args.spp:
            ref = render(args.binary, scene, work, f"{name}_ref_spp{spp}",
                         ["--accel", "reference", "--spp", str(spp)], size)
            for isect in intersectors:
                for density in args.densities:
                    tag = f"{name}_{isect or 'default'}_d{density:g}_spp{spp}"
                    extra = ["--grid-density", str(density), "--spp", str(spp),
                             "--repeat", str(args.repeat)]
                    if isect:
                        extra += ["--intersector", isect]
                    img, pid, stats = render(args.binary, scene, work, tag, extra, size)
                    row = {"chart": "time_error", "scene": name, "intersector": isect or "default",
                           "density": density, "spp": spp, "scale": 1.0, "ray_offset": "robust",
                           "frame_ms": stats.get("frame_ms")}
                    row.update(compare(img, pid, ref))
                    rows.append(row)
                    print(f"{tag}: {row['frame_ms']:.1f} ms rmse {row['rmse']:.3g}", flush=True)
    # (a') model no more than the scene needs: sampling and depth settings against a
    # converged render (32 jittered samples per pixel, full depth).
    sampling = [("1 spp", ["--spp", "1"]), ("4 spp", ["--spp", "4"]), ("9 spp", ["--spp", "9"]),
                ("adaptive 1+8", ["--aa", "adaptive", "--aa-samples", "8"]),
                ("adaptive 1+4", ["--aa", "adaptive", "--aa-samples", "4"]),
                ("9 spp, depth cut 0.05", ["--spp", "9", "--min-path-weight", "0.05"]),
                ("9 spp, max depth 2", ["--spp", "9", "--max-depth", "2"])]
    if has_flag(args.binary, "--aa"):
        for scene in args.scenes:
            name = os.path.splitext(os.path.basename(scene))[0]
            conv = render(args.binary, scene, work, f"{name}_converged", ["--spp", "32"], size)
            for label, extra in sampling:
                tag = f"{name}_sampling_{label.replace(' ', '_').replace(',', '')}"
                img, pid, stats = render(args.binary, scene, work, tag,
                                         extra + ["--repeat", str(args.repeat)], size)
                row = {"chart": "sampling", "scene": name, "intersector": "mt", "density": "auto",
                       "spp": label, "scale": 1.0, "ray_offset": "robust",
                       "frame_ms": stats.get("frame_ms"), "rays": stats["rays"]["total"]}
                row.update(compare(img, pid, conv, display=True))
                rows.append(row)
                print(f"{tag}: {row['frame_ms']:.1f} ms, {row['rays']} rays, rmse {row['rmse']:.3g}",
                      flush=True)
    # (b) error against scene scale.
    for scale in args.scales:
        scene = scaled_copy(args.scale_scene, scale, work)
        ref = render(args.binary, scene, work, f"scale{scale:g}_ref",
                     ["--accel", "reference", "--ray-offset", "robust"], size)
        for offset in ("epsilon=1e-4", "robust"):
            tag = f"scale{scale:g}_{offset.replace('=', '')}"
            img, pid, stats = render(args.binary, scene, work, tag, ["--ray-offset", offset], size)
            row = {"chart": "scale", "scene": os.path.basename(args.scale_scene),
                   "intersector": "default", "density": "auto", "spp": 1, "scale": scale,
                   "ray_offset": offset, "frame_ms": stats.get("frame_ms")}
            row.update(compare(img, pid, ref))
            rows.append(row)
            print(f"{tag}: rmse {row['rmse']:.3g}", flush=True)

    csv_path = os.path.join(args.out, "accuracy.csv")
    bench.write_csv(csv_path, rows)
    charts(rows, args.out)
    shutil.rmtree(work, ignore_errors=True)
    print(f"wrote {csv_path}")
    return 0


def charts(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    te = [r for r in rows if r["chart"] == "time_error"]
    if te:
        fig, ax = plt.subplots(figsize=(7, 5))
        pts = [(r["frame_ms"], r["rmse"]) for r in te]
        for isect in sorted({r["intersector"] for r in te}):
            sel = [r for r in te if r["intersector"] == isect]
            ax.scatter([r["frame_ms"] for r in sel], [r["rmse"] for r in sel], label=isect)
            for r in sel:
                ax.annotate(f"d{r['density']:g}/spp{r['spp']}", (r["frame_ms"], r["rmse"]),
                            fontsize=7)
        front = pareto(pts)
        ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "k--",
                label="Pareto front")
        ax.set_xlabel("frame time (ms)")
        ax.set_ylabel("RMSE against the double-precision reference")
        ax.set_title("Time against error")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "accuracy_time_error.png"), dpi=120)
        plt.close(fig)
    sm = [r for r in rows if r["chart"] == "sampling"]
    if sm:
        fig, ax = plt.subplots(figsize=(7, 5))
        pts = [(r["frame_ms"], r["rmse"]) for r in sm]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts])
        for r in sm:
            ax.annotate(f"{r['spp']} ({r['rays'] / 1e3:.0f}k rays)", (r["frame_ms"], r["rmse"]),
                        fontsize=7)
        front = sorted(pareto(pts), key=lambda i: pts[i][0])
        ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "k--", label="Pareto front")
        ax.set_xlabel("frame time (ms)")
        ax.set_ylabel("RMSE against a 32-spp render (display: clamped to [0, 1])")
        ax.set_title("Sampling and depth: time against error")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "accuracy_sampling.png"), dpi=120)
        plt.close(fig)
    sc = [r for r in rows if r["chart"] == "scale"]
    if sc:
        fig, ax = plt.subplots(figsize=(7, 5))
        for offset in sorted({r["ray_offset"] for r in sc}):
            sel = sorted((r for r in sc if r["ray_offset"] == offset), key=lambda r: r["scale"])
            ax.plot([r["scale"] for r in sel], [max(r["rmse"], 1e-9) for r in sel], "o-",
                    label=f"--ray-offset {offset}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("scene scale")
        ax.set_ylabel("RMSE against the double-precision reference (floor 1e-9)")
        ax.set_title("Error against scene scale")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "accuracy_scale.png"), dpi=120)
        plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
