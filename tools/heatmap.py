#!/usr/bin/env python3
"""False-colour pictures of gridrt's per-pixel AOVs (gridrt --aov NAME=FILE.exr):

    .venv/bin/python tools/heatmap.py pe.exr pe.png            # kind guessed from the name
    .venv/bin/python tools/heatmap.py tests.exr tests.png --kind tests --max 200

  pe       winning processing element: each PE index gets its own hashed colour, so
           neighbouring voxels are told apart; -1 (a miss) is black. Same size as the image.
  tests    ray-triangle tests of the primary ray   } viridis colour map with a colour bar
  listlen  PEs in the ray's traversal list         } (0 .. max, max = the image's maximum)

Needs the packages of tools/requirements.txt (tools/setup_python.sh makes .venv).
"""
import argparse
import os
import sys

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError as missing:  # one line, not a traceback, when run outside .venv
    sys.exit(f"{os.path.basename(sys.argv[0])}: the Python package '{missing.name}' is missing: "
             f"run tools/setup_python.sh, then .venv/bin/python {sys.argv[0]} ...")

KINDS = ("pe", "tests", "listlen")


def read_single_channel(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit("heatmap: cannot read %s: %s" % (path, buf.geterror()))
    pixels = buf.get_pixels(oiio.FLOAT)  # (height, width, channels), row 0 = top
    return np.asarray(pixels)[:, :, 0]


def guess_kind(path):
    stem = os.path.splitext(os.path.basename(path))[0].lower()
    for kind in ("listlen", "tests", "pe"):  # "pe" last: it is a substring of other names
        if kind in stem:
            return kind
    sys.exit("heatmap: cannot guess the AOV kind of %s: pass --kind %s" % (path, "|".join(KINDS)))


def hashed_colours(ids):
    """A distinct, stable colour per non-negative integer id (a PCG-style hash of the id,
    mapped to a bright hue); -1 and other negative ids are black."""
    v = ids.astype(np.int64).clip(min=0).astype(np.uint32)
    v = v * np.uint32(747796405) + np.uint32(2891336453)
    v = ((v >> ((v >> np.uint32(28)) + np.uint32(4))) ^ v) * np.uint32(277803737)
    v = (v >> np.uint32(22)) ^ v
    hue = (v & np.uint32(0xFFFF)).astype(np.float64) / 65536.0
    sat = 0.55 + 0.45 * ((v >> np.uint32(16)) & np.uint32(0xFF)) / 255.0
    val = 0.70 + 0.30 * ((v >> np.uint32(24)) & np.uint32(0xFF)) / 255.0
    import matplotlib.colors
    rgb = matplotlib.colors.hsv_to_rgb(np.stack([hue, sat, val], axis=-1))
    rgb[ids < 0] = 0.0
    return (rgb * 255.0 + 0.5).astype(np.uint8)


def write_pe(values, out):
    import matplotlib.pyplot as plt
    plt.imsave(out, hashed_colours(np.rint(values)))


def write_scalar(values, out, kind, vmax):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    height, width = values.shape
    vmax = vmax if vmax is not None else max(float(values.max()), 1.0)
    dpi = 100.0
    # The image at its own resolution, plus room on the right for the colour bar.
    fig = plt.figure(figsize=((width + 110) / dpi, (height + 20) / dpi), dpi=dpi)
    ax = fig.add_axes([10 / (width + 110), 10 / (height + 20), width / (width + 110),
                       height / (height + 20)])
    shown = ax.imshow(values, cmap="viridis", vmin=0.0, vmax=vmax, interpolation="nearest")
    ax.set_axis_off()
    bar_ax = fig.add_axes([(width + 20) / (width + 110), 0.1, 12 / (width + 110), 0.8])
    label = {"tests": "ray-triangle tests", "listlen": "PEs in the list"}[kind]
    fig.colorbar(shown, cax=bar_ax, label=label)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("input", help="an AOV .exr written by gridrt --aov")
    parser.add_argument("output", help="the picture (.png)")
    parser.add_argument("--kind", choices=KINDS, help="what the AOV holds (default: from the name)")
    parser.add_argument("--max", type=float, help="tests/listlen: value at the top of the colour map")
    args = parser.parse_args()
    if not os.path.isfile(args.input):
        sys.exit("heatmap: %s: no such file" % args.input)
    kind = args.kind or guess_kind(args.input)
    values = read_single_channel(args.input)
    if kind == "pe":
        write_pe(values, args.output)
    else:
        write_scalar(values, args.output, kind, args.max)
    print("heatmap: %s (%s) -> %s" % (args.input, kind, args.output))


if __name__ == "__main__":
    main()
