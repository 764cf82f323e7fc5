#!/usr/bin/python3
"""gridrt, except on a machine where FARM_BROKEN_WORKER is set: there its renders fail as
gridrt's do without an OpenCL device (one line, exit 1), while --version still answers, as
it does without a device. The real gridrt is GRIDRT_BINARY, else build/gridrt."""
import os
import sys

if os.environ.get("FARM_BROKEN_WORKER") and sys.argv[1:] != ["--version"]:
    print("gridrt: no OpenCL platform found (the test's broken worker)", file=sys.stderr)
    sys.exit(1)
gridrt = os.environ.get("GRIDRT_BINARY") or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "gridrt")
os.execv(gridrt, [gridrt, *sys.argv[1:]])
