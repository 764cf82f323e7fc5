"""The farm's command line: its own options, the scene, -o, and the gridrt options it passes
on to every task. A bad value is a one-line UsageError (exit 2)."""
import argparse
import os
import re

from .executables import MERGE_TILES

# The gridrt options the farm passes on to every task, by kind: flags take no value, the
# others exactly one (`--opt VALUE` or `--opt=VALUE`); this is also how the scene is told
# apart from option values. An option in none of these lists is refused, so a worker runs
# gridrt only with options the farm knows (tests/farm checks them against gridrt --help).
FORWARDED_FLAGS = {"--alpha", "--pe-interrupt", "--primary-only", "--stats", "-q", "--quiet",
                   "-v", "--verbose"}
FORWARDED_VALUES = {"--width", "--height", "--spp", "--max-depth", "--device", "--threads",
                    "--wave-rays", "--accel", "--grid", "--grid-density", "--pe-layout",
                    "--transfer", "--background", "--ambient", "--ray-offset",
                    "--intersector", "--shading", "--aa", "--aa-samples", "--aa-threshold",
                    "--min-path-weight", "--camera", "--look-at", "--fov", "--time", "--fps",
                    "--animation"}
# gridrt options the farm sets itself or cannot honour, with the reason it gives. None of
# them reaches a worker: every file a task writes is in its own temporary folder.
REFUSED = {
    "--crop": "the farm crops the tiles itself (--tiles)",
    "--crop-output": "the farm crops the tiles itself (--tiles)",
    "--aov": "AOVs are not merged by the farm; render them with gridrt",
    "--aov-file": "AOVs are not merged by the farm; render them with gridrt",
    "--stats-json": "the farm writes its own statistics (--farm-stats)",
    "--repeat": "repeated frames are for timing one process; use gridrt",
    "--list-devices": "list devices with gridrt on each machine",
    "--force": "-o is required, and replaces an existing file as gridrt's -o does",
    "--format": "the output's format is -o's extension",
    "--version": "ask gridrt",
    "--view": "the viewer's window is gridrt's own (gridrt --view)",
}
REFUSED_FLAGS = {"--force", "--list-devices", "--version", "--view"}
OUTPUT_EXTENSIONS = (".png", ".jpg", ".jpeg", ".exr", ".tif", ".tiff")
# A printf conversion of the frame number in a sequence's -o: %d or %04d.
FRAME_CONVERSION = re.compile(r"%0?\d*d")
MAX_SIZE = 65536  # gridrt's --width/--height bound


class UsageError(Exception):
    """A bad command line: one line, exit 2."""


class OneLineParser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def parse_tiles(text):
    m = re.fullmatch(r"(\d+)x(\d+)", text)
    if not m or int(m.group(1)) < 1 or int(m.group(2)) < 1:
        raise UsageError(f"--tiles: expected NXxNY with NX, NY >= 1 (e.g. 4x4), got '{text}'")
    return int(m.group(1)), int(m.group(2))


def parse_frames(text):
    m = re.fullmatch(r"(-?\d+):(-?\d+)", text)
    if not m or int(m.group(1)) > int(m.group(2)):
        raise UsageError(f"--frames: expected A:B with integers A <= B, got '{text}'")
    return int(m.group(1)), int(m.group(2))


def parser():
    p = OneLineParser(
        prog="gridrt-farm", add_help=True, allow_abbrev=False,
        usage="gridrt-farm [--scheduler tls://HOST:PORT --tls-ca-file CA --tls-cert CERT "
              "--tls-key KEY] [--tiles NXxNY] [--frames A:B] [--gridrt PATH] [SCENE] -o OUT "
              "[gridrt options...]",
        description="Renders a gridrt job's tiles and frames on a Dask cluster and merges "
                    "each frame into OUT, bit for bit what one gridrt process writes.",
        epilog="gridrt's options go to gridrt on every task (gridrt --help); the farm "
               "sets --crop, --crop-output, --width, --height and -q itself and refuses "
               "those it cannot honour or does not know. docs/farm.md.")
    p.add_argument("--scheduler", metavar="tls://HOST:PORT", help="the Dask scheduler, "
                   "tls://HOST:PORT (tcp:// on loopback, or with --insecure); without it a "
                   "local cluster of --workers processes is started on this machine")
    p.add_argument("--tls-ca-file", metavar="CA", help="tls://: the certificate authority "
                   "the scheduler's certificate must be signed by (PEM)")
    p.add_argument("--tls-cert", metavar="CERT", help="tls://: this client's certificate "
                   "(PEM), signed by the CA the scheduler trusts")
    p.add_argument("--tls-key", metavar="KEY", help="tls://: the private key of --tls-cert")
    p.add_argument("--insecure", action="store_true", help="allow tcp:// to an address that "
                   "is not loopback: unencrypted, and whoever reaches the scheduler runs code "
                   "on every worker")
    p.add_argument("--connect-timeout", type=float, default=10.0, metavar="SECONDS",
                   help="how long to try to reach --scheduler (default 10)")
    p.add_argument("--strict", action="store_true", help="refuse the job when a worker runs "
                   "another gridrt build (by default it is left out, with a warning)")
    p.add_argument("--workers", type=int, default=2, metavar="N",
                   help="local cluster: worker processes (default 2)")
    p.add_argument("--tiles", type=parse_tiles, default=None, metavar="NXxNY",
                   help="tiles of each frame, NXxNY (default 4x4 for one frame, 1x1 with --frames)")
    p.add_argument("--frames", type=parse_frames, default=None, metavar="A:B",
                   help="frames A:B of an animation (gridrt --frames); OUT a printf pattern")
    p.add_argument("--gridrt", metavar="PATH", help="the gridrt the workers run (default: "
                   "the gridrt beside gridrt-farm, else this source tree's build/gridrt, "
                   "else gridrt on PATH; on each worker alike)")
    p.add_argument("--merge-tiles", metavar="PATH", help=f"the tile merger ({MERGE_TILES}) "
                   "that merges the frames here (default: the one beside gridrt, in gridrt's "
                   "build, beside this tool, or on PATH)")
    p.add_argument("--shared-scene", action="store_true",
                   help="the workers read SCENE from its path (a shared file system) "
                   "instead of receiving it with the tasks")
    p.add_argument("--resume", action="store_true",
                   help="keep the frames already written and render only the missing ones")
    p.add_argument("--tile-order", choices=["raster", "centre"], default="raster",
                   help="raster (rows from the top) or centre (nearest the centre first)")
    p.add_argument("--retries", type=int, default=2, metavar="N",
                   help="a task gridrt fails is tried again on another worker this many "
                   "times at most (default 2)")
    p.add_argument("--wait-for-workers", type=float, default=60.0, metavar="SECONDS",
                   help="how long the job waits while no worker of its gridrt build is alive "
                   "(default 60)")
    p.add_argument("--farm-stats", metavar="FILE", help="write the job's statistics as JSON")
    p.add_argument("-o", "--output", required=True, metavar="OUT", help="output image, or a printf pattern "
                   "(out_%%04d.png) with --frames")
    return p


def split_gridrt_options(tokens):
    """Splits what argparse did not know into the scene (the first bare word) and gridrt's
    options as (flag, value or None) pairs, in order."""
    scene, options, k = None, [], 0
    while k < len(tokens):
        t = tokens[k]
        if t.startswith("-") and len(t) > 1 and not _is_number(t):
            if "=" in t and t.startswith("--"):
                flag, value = t.split("=", 1)
                options.append((flag, value))
            elif t in FORWARDED_FLAGS or t in REFUSED_FLAGS:
                options.append((t, None))
            elif t not in FORWARDED_VALUES and t not in REFUSED:
                raise UsageError(f"{t}: not a gridrt option the farm passes on "
                                 "(gridrt-farm --help, docs/farm.md)")
            else:
                if k + 1 >= len(tokens):
                    raise UsageError(f"{t}: expected a value")
                options.append((t, tokens[k + 1]))
                k += 1
        elif scene is None:
            scene = t
        else:
            raise UsageError(f"one scene only: got '{scene}' and '{t}'")
        k += 1
    return scene, options


def _is_number(t):
    try:
        float(t)
        return True
    except ValueError:
        return False


def _size(options, flag):
    values = [v for f, v in options if f == flag]
    if not values:
        return None
    v = values[-1]
    if not re.fullmatch(r"\d+", v) or not 1 <= int(v) <= MAX_SIZE:
        raise UsageError(f"{flag}: expected an integer in 1..{MAX_SIZE}, got '{v}'")
    return int(v)


class FarmCommand:
    """The parsed command: the farm's settings, the scene and gridrt's options (without
    --width, --height and -q, which the farm gives every task itself)."""

    def __init__(self, argv):
        known, rest = parser().parse_known_args(argv)
        self.__dict__.update(vars(known))
        self.scene, options = split_gridrt_options(rest)
        for flag, _ in options:
            if flag in REFUSED:
                raise UsageError(f"{flag}: not with the farm ({REFUSED[flag]})")
            if flag == "--frames":
                raise UsageError("--frames: give it once")
        self.width, self.height = _size(options, "--width"), _size(options, "--height")
        self.quiet = any(f in ("-q", "--quiet") for f, _ in options)
        self.gridrt_options = [(f, v) for f, v in options
                               if f not in ("--width", "--height", "-q", "--quiet")]
        if self.workers < 1:
            raise UsageError(f"--workers: expected at least 1, got {self.workers}")
        if not self.connect_timeout > 0:
            raise UsageError(f"--connect-timeout: expected seconds > 0, got {self.connect_timeout}")
        if not self.wait_for_workers > 0:
            raise UsageError(f"--wait-for-workers: expected seconds > 0, got {self.wait_for_workers}")
        if self.retries < 0:
            raise UsageError(f"--retries: expected 0 or more, got {self.retries}")
        if self.tiles is None:
            self.tiles = (1, 1) if self.frames else (4, 4)
        self._check_output()

    def _check_output(self):
        ext = os.path.splitext(self.output)[1].lower()
        if ext not in OUTPUT_EXTENSIONS:
            raise UsageError(f"-o: unsupported output format '{ext or '(none)'}' "
                             "(use .png, .jpg or .exr)")
        conversions = FRAME_CONVERSION.findall(self.output.replace("%%", ""))
        if self.frames and len(conversions) != 1:
            raise UsageError(f"-o: with --frames the output must hold one %d or %04d for the "
                             f"frame number, got '{self.output}'")
        directory = os.path.dirname(self.output) or "."
        if not os.path.isdir(directory):
            raise UsageError(f"-o: directory '{directory}' does not exist")
        if not os.access(directory, os.W_OK):
            raise UsageError(f"-o: directory '{directory}' is not writable")

    def frame_numbers(self):
        """The frames to render: None for a still, else the numbers A..B."""
        if not self.frames:
            return [None]
        return list(range(self.frames[0], self.frames[1] + 1))

    def output_of(self, frame):
        return self.output if frame is None else _expand(self.output, frame)


def _expand(pattern, frame):
    """The pattern's one %d/%0Nd replaced by the frame number (%% stays a percent sign)."""
    parts = pattern.split("%%")
    for k, part in enumerate(parts):
        m = FRAME_CONVERSION.search(part)
        if m:
            parts[k] = part[:m.start()] + (m.group(0) % frame) + part[m.end():]
            break
    return "%".join(parts)
