#!/usr/bin/python3
"""gridrt as a test's worker has it: $FARM_OTHER_GRIDRT (another build) where that is set,
else the real one (GRIDRT_BINARY, else build/gridrt); each run's arguments, one line, are
appended to $FARM_WORKER_LOG where that is set, so a test can tell what a worker ran."""
import os
import sys

log = os.environ.get("FARM_WORKER_LOG")
if log:
    with open(log, "a") as f:
        f.write(" ".join(sys.argv[1:]) + "\n")
gridrt = os.environ.get("FARM_OTHER_GRIDRT") or os.environ.get("GRIDRT_BINARY") or \
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "gridrt")
os.execv(gridrt, [gridrt, *sys.argv[1:]])
