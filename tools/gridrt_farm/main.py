"""gridrt-farm's entry point: the command line, the scene, the cluster, the job, the summary.
Exit status: 0 done, 2 a usage error (the farm's or gridrt's), 1 anything else; every error
is one line on stderr."""
import json
import os
import sys

from . import cluster
from .command_line import FarmCommand, UsageError
from .job import FarmJob, JobFailed, summary_numbers
from .merge import MergeError
from .progress import summary_line
from .scene_bundle import DEFAULT_HEIGHT, DEFAULT_WIDTH, SceneBundle, SceneError, camera_widths
from .tiles import split

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILT_GRIDRT = os.path.join(ROOT, "build", "gridrt")


def merge_tiles_beside(gridrt):
    """tools/gridrt-merge-tiles of the build the gridrt comes from, else of this tree's build."""
    beside = os.path.join(os.path.dirname(gridrt), "tools", "gridrt-merge-tiles")
    return beside if os.path.isfile(beside) else os.path.join(ROOT, "build", "tools",
                                                              "gridrt-merge-tiles")


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


def run(argv):
    cmd = FarmCommand(argv)
    gridrt = os.path.abspath(cmd.gridrt) if cmd.gridrt else BUILT_GRIDRT
    if not cmd.scheduler and not os.access(gridrt, os.X_OK):
        raise UsageError(f"--gridrt: '{gridrt}' is not an executable (build it, or name one)")
    merge_tiles = cmd.merge_tiles or merge_tiles_beside(gridrt)
    if not os.access(merge_tiles, os.X_OK):
        raise UsageError(f"gridrt-merge-tiles is not built at '{merge_tiles}'")
    scene, shown, document = prepare_scene(cmd)
    size = image_size(cmd, document)
    try:
        split(size[0], size[1], *cmd.tiles)
    except ValueError as e:
        raise UsageError(f"--tiles: {e}") from None
    client, local = cluster.open_client(cmd.scheduler, cmd.workers)
    try:
        dashboard = cluster.dashboard_address(client)
        if dashboard and not cmd.quiet:
            print(f"gridrt-farm: dashboard {dashboard}", file=sys.stderr)
        stats = FarmJob(client, cmd, size, scene, shown, gridrt, merge_tiles).run()
    finally:
        cluster.close(client, local)
    if cmd.farm_stats:
        with open(cmd.farm_stats, "w") as f:
            json.dump(summary_numbers(stats), f, indent=1)
    if not cmd.quiet:
        print(summary_line(stats), file=sys.stderr)
    return 0


def main(argv):
    try:
        return run(argv)
    except UsageError as e:
        print(f"gridrt-farm: {e}", file=sys.stderr)
        return 2
    except (SceneError, cluster.ClusterError, MergeError) as e:
        print(f"gridrt-farm: {e}", file=sys.stderr)
        return 1
    except JobFailed as e:
        print(str(e), file=sys.stderr)
        return e.code
    except KeyboardInterrupt:
        print("gridrt-farm: interrupted; the frames written are kept (rerun with --resume)",
              file=sys.stderr)
        return 130
