#!/usr/bin/env python3
"""Compare two renders: RMSE, PSNR and max error (OpenImageIO ImageBufAlgo.compare), and,
given primitive-id AOVs (EXR, -1 = miss), the share of pixels whose primitive differs and
whose hit/miss differs.

    compare_renders.py A B [--primid-a PA --primid-b PB] [--json]

The functions are also imported by tools/accuracy_sweep.py. Run with .venv/bin/python
(tools/setup_python.sh)."""
import argparse
import json
import math
import os
import sys

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError as missing:  # one line, not a traceback, when run outside .venv
    sys.exit(f"{os.path.basename(sys.argv[0])}: the Python package '{missing.name}' is missing: "
             f"run tools/setup_python.sh, then .venv/bin/python {sys.argv[0]} ...")


# Extensions whose pixels are 8-bit sRGB codes; .exr/.hdr/.tif hold linear values.
ENCODED = (".png", ".jpg", ".jpeg")


def _read(path):
    if not os.path.isfile(path):
        raise RuntimeError(f"{path}: no such file")
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise RuntimeError(f"{path}: {buf.geterror()}")
    return buf


def image_error(path_a, path_b, display=False):
    """RMSE, PSNR (dB, peak 1) and max abs error over all channels of A against B.
    display=True clamps both to [0, 1] first: the error a viewer of the PNG would see,
    not dominated by a few very bright pixels near a light."""
    if path_a.lower().endswith(ENCODED) != path_b.lower().endswith(ENCODED):
        raise RuntimeError(f"{path_a} and {path_b}: one holds sRGB codes, the other linear "
                           "values; compare two PNGs or two EXRs")
    a, b = _read(path_a), _read(path_b)
    if (a.spec().width, a.spec().height) != (b.spec().width, b.spec().height):
        raise RuntimeError(f"{path_a} and {path_b} differ in size")
    if display:
        a = oiio.ImageBufAlgo.clamp(a, 0.0, 1.0)
        b = oiio.ImageBufAlgo.clamp(b, 0.0, 1.0)
    r = oiio.ImageBufAlgo.compare(a, b, 1e-6, 1e-6)
    rmse = float(r.rms_error)
    psnr = float(r.PSNR) if rmse > 0 else math.inf
    return {"rmse": rmse, "psnr": psnr, "max_error": float(r.maxerror),
            "mean_error": float(r.meanerror)}


def primid_difference(path_a, path_b):
    """Shares of pixels whose primitive id differs, and whose hit/miss differs."""
    a = _read(path_a).get_pixels(oiio.FLOAT)[..., 0]
    b = _read(path_b).get_pixels(oiio.FLOAT)[..., 0]
    if a.shape != b.shape:
        raise RuntimeError(f"{path_a} and {path_b} differ in size")
    n = a.size
    return {"prim_differs": float(np.count_nonzero(a != b)) / n,
            "hit_miss_differs": float(np.count_nonzero((a < 0) != (b < 0))) / n}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--primid-a")
    p.add_argument("--primid-b")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    args = p.parse_args(argv)
    if bool(args.primid_a) != bool(args.primid_b):
        p.error("--primid-a and --primid-b go together")
    try:
        result = image_error(args.a, args.b)
        if args.primid_a:
            result.update(primid_difference(args.primid_a, args.primid_b))
    except RuntimeError as e:
        print(f"compare_renders: {e}", file=sys.stderr)
        return 1
    if args.json:
        # Strict JSON: an exact match has no finite PSNR, written as null (not Infinity).
        print(json.dumps({k: (v if math.isfinite(v) else None) for k, v in result.items()},
                         allow_nan=False))
    else:
        for k, v in result.items():
            print(f"{k:18s} {v:.6g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
