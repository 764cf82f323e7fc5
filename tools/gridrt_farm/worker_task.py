"""What a worker runs for one task: gridrt on one tile of one frame, in a folder of its own.
The module is sent to the workers by value (cloudpickle), so it imports nothing but the
standard library and the workers need no copy of the farm.

A task returns a dict, never raises for gridrt's own failures: the client decides whether
to try again elsewhere (gridrt exit 1, or a crash) or to stop (exit 2, a usage error)."""
import glob
import json
import os
import shutil
import subprocess
import tempfile
import time

SCENE_CACHE = "gridrt-farm-scenes"  # per machine, under the temporary folder


def scene_on_this_machine(bundle):
    """The path of the shipped scene on this machine, written once per digest: into a
    fresh folder renamed into place, so concurrent tasks never see half a scene."""
    root = os.path.join(tempfile.gettempdir(), SCENE_CACHE)
    folder = os.path.join(root, bundle["digest"])
    if not os.path.isdir(folder):
        os.makedirs(root, exist_ok=True)
        fresh = tempfile.mkdtemp(prefix=".incoming-", dir=root)
        for name, data in bundle["files"].items():
            target = os.path.join(fresh, name)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as f:
                f.write(data)
        try:
            os.rename(fresh, folder)
        except OSError:  # another task put it there first
            shutil.rmtree(fresh, ignore_errors=True)
    return os.path.join(folder, bundle["main"])


def scene_data(bundle):
    """The scene bundle as a task's result, so that Dask can make a lost copy again."""
    return bundle


def worker_address():
    try:
        from distributed import get_worker
        return get_worker().address
    except (ImportError, ValueError):
        return "local"


def last_line(text):
    lines = [l for l in text.splitlines() if l.strip()]
    return lines[-1] if lines else ""


def render_tile(spec, scene):
    """spec: gridrt, options (argv after the scene), frame (None or K), crop, scene_shown
    (the user's name of the scene); scene: None (built-in), a path, or a shipped bundle."""
    started = time.monotonic()
    result = {"worker": worker_address(), "ok": False}
    work = tempfile.mkdtemp(prefix="gridrt-farm-task-")
    try:
        argv = [spec["gridrt"]]
        shown_as = None
        if isinstance(scene, dict):
            shown_as = scene_on_this_machine(scene)
            argv.append(shown_as)
        elif scene is not None:
            argv.append(scene)
        argv += spec["options"]
        if spec["frame"] is not None:
            argv += ["--frames", f"{spec['frame']}:{spec['frame']}",
                     "-o", os.path.join(work, "tile_%06d.exr")]
        else:
            argv += ["-o", os.path.join(work, "tile.exr")]
        stats_path = os.path.join(work, "stats.json")
        argv += ["--crop", spec["crop"], "--crop-output", "window", "--stats-json", stats_path,
                 "-q"]
        try:
            proc = subprocess.run(argv, capture_output=True, text=True)
        except OSError as e:
            result.update(code=1, message=f"gridrt-farm: cannot run '{spec['gridrt']}' on "
                          f"{result['worker']}: {e.strerror}")
            return result
        if proc.returncode != 0:
            message = last_line(proc.stderr)
            if shown_as:
                message = message.replace(shown_as, spec["scene_shown"])
            if proc.returncode < 0:
                message = f"gridrt-farm: gridrt died of signal {-proc.returncode} on " \
                          f"{result['worker']}" + (f" ({message})" if message else "")
            result.update(code=proc.returncode, message=message or
                          f"gridrt-farm: gridrt exited {proc.returncode} without a message")
            return result
        written = sorted(glob.glob(os.path.join(work, "tile*.exr")))
        if len(written) != 1:
            result.update(code=1, message=f"gridrt-farm: gridrt wrote {len(written)} tile "
                          f"files for one task on {result['worker']} (expected 1)")
            return result
        with open(written[0], "rb") as f:
            result["tile"] = f.read()
        with open(stats_path) as f:
            stats = json.load(f)
        result.update(ok=True, rays=stats.get("rays", {}).get("total", 0),
                      **{k: stats.get(k, 0.0) for k in ("frame_ms", "load_ms", "build_ms",
                                                        "compile_ms")})
        return result
    finally:
        shutil.rmtree(work, ignore_errors=True)
        result["seconds"] = time.monotonic() - started
