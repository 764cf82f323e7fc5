"""Where the farm finds its two executables: gridrt, which the workers run, and the tile
merger, which runs here. Installed, both sit beside gridrt-farm (P/bin); in a source tree,
in its build/ folder; else on PATH."""
import os

# The first candidate that is an executable file here (a bare name on PATH), or None: the
# workers' own rule (worker_task.py), so that here and there agree.
from .worker_task import resolve_gridrt as first_executable

GRIDRT = "gridrt"
MERGE_TILES = "gridrt-merge-tiles"  # the tile merger's file name
# The source tree this package belongs to, when it runs from one (tools/gridrt_farm/).
SOURCE_TREE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def gridrt_candidates(program, given=None):
    """The gridrt paths to try, first first: --gridrt alone when given; else the gridrt
    beside the farm's program, the source tree's build/gridrt, and `gridrt` on PATH (a bare
    name, looked up on the machine that runs it). Each worker takes the first it can run."""
    if given:
        return [os.path.abspath(given)]
    beside = os.path.join(os.path.dirname(os.path.abspath(program)), GRIDRT)
    return [beside, os.path.join(SOURCE_TREE, "build", GRIDRT), GRIDRT]


def merge_tiles_for(gridrt, program):
    """The tile merger of gridrt's build or installation, else beside the farm, in the
    source tree's build, or on PATH; None when there is none."""
    folders = [os.path.dirname(gridrt), os.path.join(os.path.dirname(gridrt), "tools")] \
        if gridrt else []
    folders += [os.path.dirname(os.path.abspath(program)),
                os.path.join(SOURCE_TREE, "build", "tools")]
    return first_executable([os.path.join(f, MERGE_TILES) for f in folders] + [MERGE_TILES])
