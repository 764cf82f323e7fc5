#!/usr/bin/python3
"""gridrt as a test's worker has it: $FARM_OTHER_GRIDRT (another build) where that is set,
else the real one (GRIDRT_BINARY, else build/gridrt); each run's arguments, one line, are
appended to $FARM_WORKER_LOG where that is set, so a test can tell what a worker ran; and
where $FARM_WORKER_GATE is set, a render (not --version) waits until that file exists, so
a test can hold a worker's tile back."""
import os
import sys
import time

GATE_SECONDS = 120  # the longest a render waits at the gate (a test that died never opens it)
GATE_POLL_SECONDS = 0.05

log = os.environ.get("FARM_WORKER_LOG")
if log:
    with open(log, "a") as f:
        f.write(" ".join(sys.argv[1:]) + "\n")
gate = os.environ.get("FARM_WORKER_GATE")
if gate and sys.argv[1:] != ["--version"]:
    deadline = time.monotonic() + GATE_SECONDS
    while not os.path.exists(gate) and time.monotonic() < deadline:
        time.sleep(GATE_POLL_SECONDS)
gridrt = os.environ.get("FARM_OTHER_GRIDRT") or os.environ.get("GRIDRT_BINARY") or \
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "gridrt")
os.execv(gridrt, [gridrt, *sys.argv[1:]])
