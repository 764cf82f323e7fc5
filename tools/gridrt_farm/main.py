"""gridrt-farm's entry point: the command line, the scene, the cluster, the job, the summary.
Exit status: 0 done, 2 a usage error (the farm's or gridrt's), 1 anything else; every error
is one line on stderr."""
import json
import os
import sys

from . import cluster, executables, worker_task
from .build_check import BuildRefused
from .command_line import FarmCommand, UsageError
from .job import FarmJob, JobFailed, summary_numbers
from .merge import MergeError
from .progress import summary_line
from .security import connection_security
from .scene_bundle import DEFAULT_HEIGHT, DEFAULT_WIDTH, SceneBundle, SceneError, camera_widths
from .tiles import split

def image_size(cmd, document):
    """As gridrt sizes it: as given; with neither --width nor --height, the scene camera's
    aspect at the default height (a tile's --crop would otherwise keep 640x480)."""
    if cmd.width or cmd.height:
        return cmd.width or DEFAULT_WIDTH, cmd.height or DEFAULT_HEIGHT
    widths = camera_widths(document)
    if len(widths) > 1:
        raise UsageError("the scene's cameras give different image sizes: give --width and "
                         "--height")
    return (widths.pop() if widths else DEFAULT_WIDTH), DEFAULT_HEIGHT


def prepare_scene(cmd):
    """(what the tasks get, the scene's name in messages, its glTF JSON or None)."""
    if cmd.scene is None:
        return None, None, None
    if cmd.shared_scene:
        path = os.path.abspath(cmd.scene)
        document = SceneBundle(path).document if os.path.isfile(path) else None
        return path, cmd.scene, document
    bundle = SceneBundle(cmd.scene)
    shipped = {"digest": bundle.digest, "files": bundle.files, "main": bundle.main}
    return shipped, cmd.scene, bundle.document


def run(argv, program):
    cmd = FarmCommand(argv)
    security = connection_security(cmd)
    candidates = executables.gridrt_candidates(program, cmd.gridrt)
    here = executables.first_executable(candidates)
    if not cmd.scheduler and here is None:
        raise UsageError(f"--gridrt: no gridrt at {' nor '.join(candidates)} (build it, or "
                         "name one)")
    merge_tiles = cmd.merge_tiles or executables.merge_tiles_for(here, program)
    if not merge_tiles or not os.access(merge_tiles, os.X_OK):
        raise UsageError(f"{executables.MERGE_TILES} is not found beside gridrt nor on PATH "
                         f"({merge_tiles or 'give --merge-tiles'})")
    # The job's build: the gridrt here; else the one most workers run (build_check.py).
    expected = worker_task.gridrt_identity([here]) if here else None
    if expected is not None and "error" in expected:
        raise UsageError(f"--gridrt: {expected['error']}")
    scene, shown, document = prepare_scene(cmd)
    size = image_size(cmd, document)
    try:
        split(size[0], size[1], *cmd.tiles)
    except ValueError as e:
        raise UsageError(f"--tiles: {e}") from None
    client, local = cluster.open_client(cmd.scheduler, cmd.workers, security,
                                        cmd.connect_timeout)
    try:
        dashboard = cluster.dashboard_address(client)
        if dashboard and not cmd.quiet:
            print(f"gridrt-farm: dashboard {dashboard}", file=sys.stderr)
        stats = FarmJob(client, cmd, size, scene, shown, candidates, expected,
                        merge_tiles).run()
    finally:
        cluster.close(client, local)
    if cmd.farm_stats:
        with open(cmd.farm_stats, "w") as f:
            json.dump(summary_numbers(stats), f, indent=1)
    if not cmd.quiet:
        print(summary_line(stats), file=sys.stderr)
    return 0


def main(argv, program=sys.argv[0]):
    """program: the path the farm was started as (gridrt is looked for beside it)."""
    try:
        return run(argv, program)
    except UsageError as e:
        print(f"gridrt-farm: {e}", file=sys.stderr)
        return 2
    except (SceneError, cluster.ClusterError, MergeError, BuildRefused) as e:
        print(f"gridrt-farm: {e}", file=sys.stderr)
        return 1
    except JobFailed as e:
        print(str(e), file=sys.stderr)
        return e.code
    except KeyboardInterrupt:
        print("gridrt-farm: interrupted; the frames written are kept (rerun with --resume)",
              file=sys.stderr)
        return 130
