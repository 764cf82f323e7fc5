#!/usr/bin/python3
"""A stand-in for gridrt's animation interface (--frames K:K, --fps F, -o PATTERN) while
gridrt has none: frame K is the built-in scene seen with a field of view of 30 + 5K
degrees, rendered by the real gridrt (GRIDRT_BINARY, else build/gridrt) to PATTERN % K. Each frame it renders
is appended to $FARM_STAND_IN_LOG, so a test can tell which frames a job rendered; the
frame number written in the file $FARM_STAND_IN_BROKEN (when it exists) fails, as a
gridrt error does (one line, exit 1)."""
import os
import re
import sys

FIRST_FOV, FOV_STEP = 30.0, 5.0  # degrees: eight frames that all differ


def main(argv):
    gridrt = os.environ.get("GRIDRT_BINARY") or os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "gridrt")
    if argv == ["--version"]:  # the build it stands in for
        os.execv(gridrt, [gridrt, "--version"])
    out, frame, rest, k = None, None, [], 0
    while k < len(argv):
        if argv[k] == "--frames":
            a, b = argv[k + 1].split(":")
            if a != b:
                sys.exit("anim_stand_in: one frame at a time (K:K)")
            frame = int(a)
            k += 2
        elif argv[k] == "--fps":
            k += 2
        elif argv[k] in ("-o", "--output"):
            out = argv[k + 1]
            k += 2
        else:
            rest.append(argv[k])
            k += 1
    if frame is None or out is None:
        sys.exit("anim_stand_in: needs --frames K:K and -o PATTERN")
    broken = os.environ.get("FARM_STAND_IN_BROKEN")
    if broken and os.path.exists(broken):
        with open(broken) as f:
            if int(f.read()) == frame:
                print(f"gridrt: frame {frame} cannot be rendered (the test's broken frame)",
                      file=sys.stderr)
                sys.exit(1)
    log = os.environ.get("FARM_STAND_IN_LOG")
    if log:
        with open(log, "a") as f:
            f.write(f"{frame}\n")
    target = re.sub(r"%0?\d*d", lambda m: m.group(0) % frame, out, count=1)
    os.execv(gridrt, [gridrt, *rest, "--fov", str(FIRST_FOV + FOV_STEP * frame), "-o", target])


if __name__ == "__main__":
    main(sys.argv[1:])
