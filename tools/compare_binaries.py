#!/usr/bin/env python3
"""Two gridrt binaries on the speed targets, in turns: is a change slower than noise?

    python3 tools/compare_binaries.py OLD_GRIDRT [NEW_GRIDRT] [--rounds 9] [--frames 30]

NEW_GRIDRT defaults to build/gridrt. Each round runs every target once with each binary
(the order alternating from round to round), each run the median of --frames frames after
a warm-up frame (gridrt --repeat). Prints, per target, both medians over the rounds, the
ratio new/old of the medians and the range of the per-round ratios; --csv writes the rows.
Only the standard library is needed.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "scenes", "models")

# (label, statistics key, smaller is better, gridrt arguments): the targets of bench.py's
# `targets` set, the grid build included.
TARGETS = [
    ("bunny_res4 320x240 primary, ms/frame", "frame_ms", True,
     [os.path.join(MODELS, "bunny_res4.glb"), "--width", "320", "--height", "240",
      "--primary-only"]),
    ("bunny 1280x960 primary, ms/frame", "frame_ms", True,
     [os.path.join(MODELS, "bunny.glb"), "--width", "1280", "--height", "960", "--primary-only"]),
    ("bunny grid build, ms", "build_ms", True,
     [os.path.join(MODELS, "bunny.glb"), "--width", "64", "--height", "48", "--primary-only"]),
    ("default scene 640x480 Whitted depth 5, ms/frame", "frame_ms", True,
     ["--width", "640", "--height", "480", "--max-depth", "5"]),
]


def run(binary, args, frames):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        subprocess.run([binary, *args, "--repeat", str(frames), "-q", "-o",
                        os.path.join(tmp, "out.exr"), "--stats-json", stats], check=True)
        with open(stats) as f:
            return json.load(f)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("old")
    p.add_argument("new", nargs="?", default=os.path.join(ROOT, "build", "gridrt"))
    p.add_argument("--rounds", type=int, default=9)
    p.add_argument("--frames", type=int, default=30)
    p.add_argument("--csv", help="write the rows to this CSV file")
    a = p.parse_args()
    for path in (a.old, a.new):
        if not os.access(path, os.X_OK):
            sys.exit(f"compare_binaries: '{path}' is not an executable")
    if a.rounds < 1 or a.frames < 1:
        sys.exit("compare_binaries: --rounds and --frames must be at least 1")

    times = {(t[0], which): [] for t in TARGETS for which in ("old", "new")}
    for r in range(a.rounds):
        order = ("old", "new") if r % 2 == 0 else ("new", "old")
        for label, key, _, args in TARGETS:
            for which in order:
                s = run(a.old if which == "old" else a.new, args, a.frames)
                times[(label, which)].append(float(s[key]))
        print(f"round {r + 1}/{a.rounds} done", file=sys.stderr)

    rows = []
    for label, _, _, _ in TARGETS:
        old, new = times[(label, "old")], times[(label, "new")]
        ratios = [n / o for n, o in zip(new, old) if o > 0]
        rows.append({"target": label, "old_median": statistics.median(old),
                     "new_median": statistics.median(new),
                     "ratio_new_old": statistics.median(new) / statistics.median(old),
                     "round_ratio_min": min(ratios), "round_ratio_max": max(ratios)})
    for row in rows:
        print(f"{row['target']}: old {row['old_median']:.3f}, new {row['new_median']:.3f}, "
              f"new/old {row['ratio_new_old']:.3f} (rounds {row['round_ratio_min']:.2f}"
              f"-{row['round_ratio_max']:.2f})")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
