"""What a worker runs for the farm: gridrt --version (which build it is, before its first
task), and gridrt on one tile of one frame, with the options the farm built, the scene from
the job's own folder and every output in a temporary folder of the task's own. The module
is sent to the workers by value (cloudpickle), so it imports nothing but the standard
library and the workers need no copy of the farm.

A task returns a dict, never raises for gridrt's own failures: the client decides whether
to try again elsewhere (gridrt exit 1, or a crash) or to stop (exit 2, a usage error)."""
import glob
import hashlib
import json
import os
import re
import shutil
import subprocess
import tempfile
import time

SCENE_CACHE = "gridrt-farm-scenes"  # per machine, under the temporary folder
VERSION_SECONDS = 60  # the longest gridrt --version may take (it hashes its executable)
# gridrt options that name a file gridrt writes: a task passes none but its own.
OUTPUT_OPTIONS = ("-o", "--output", "--aov", "--aov-file", "--stats-json", "--crop",
                  "--crop-output", "--frames")
BUILD_LINE = re.compile(r"^build ([0-9a-f]{64})$", re.M)
KERNELS_LINE = re.compile(r"^kernels ([0-9a-f]{64})$", re.M)


def resolve_gridrt(candidates):
    """The first of the candidate paths that is an executable file on this machine (a bare
    name is looked up on PATH), or None."""
    for path in candidates:
        found = shutil.which(path) if os.sep not in path else path
        if found and os.path.isfile(found) and os.access(found, os.X_OK):
            return os.path.abspath(found)
    return None


def gridrt_identity(candidates):
    """What the gridrt this machine runs says of itself: {worker, path, version, build,
    kernels} from `gridrt --version`, or {worker, error} when it cannot say."""
    identity = {"worker": worker_address()}
    path = resolve_gridrt(candidates)
    if path is None:
        identity["error"] = "no gridrt at " + " nor ".join(candidates)
        return identity
    identity["path"] = path
    try:
        proc = subprocess.run([path, "--version"], capture_output=True, text=True,
                              timeout=VERSION_SECONDS)
    except (OSError, subprocess.TimeoutExpired) as e:
        identity["error"] = f"cannot run {path} --version: {getattr(e, 'strerror', None) or e}"
        return identity
    build, kernels = BUILD_LINE.search(proc.stdout), KERNELS_LINE.search(proc.stdout)
    first = proc.stdout.splitlines()[0] if proc.stdout.strip() else ""
    if proc.returncode != 0 or not first.startswith("gridrt ") or not build:
        identity["error"] = f"{path} --version names no gridrt build (exit {proc.returncode})"
        return identity
    identity.update(version=first[len("gridrt "):], build=build.group(1),
                    kernels=kernels.group(1) if kernels else None)
    return identity


def bundle_digest(files):
    """The digest that names a scene's files (path -> bytes) on every machine."""
    digest = hashlib.sha256()
    for name in sorted(files):
        digest.update(name.encode() + b"\0" + hashlib.sha256(files[name]).digest())
    return digest.hexdigest()[:32]


def _inside(name):
    parts = name.replace("\\", "/").split("/")
    return name and not os.path.isabs(name) and ".." not in parts and "" not in parts


def scene_on_this_machine(bundle):
    """The path of the shipped scene on this machine, written once per digest: into a
    fresh folder renamed into place, so concurrent tasks never see half a scene."""
    if bundle_digest(bundle["files"]) != bundle["digest"] or \
            not all(_inside(name) for name in bundle["files"]) or \
            os.path.basename(bundle["main"]) != bundle["main"] or \
            bundle["main"] not in bundle["files"]:
        raise ValueError("the scene sent is not a scene bundle of the farm's")
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
    """spec: gridrt (the candidate paths), build (the job's build id), options (argv after
    the scene, none naming an output), frame (None or K), crop, scene_shown (the user's name
    of the scene); scene: None (built-in), a path (--shared-scene), or a shipped bundle."""
    started = time.monotonic()
    result = {"worker": worker_address(), "ok": False}
    named = [o for o in spec["options"] if o.split("=", 1)[0] in OUTPUT_OPTIONS]
    if named:
        result.update(code=2, message=f"gridrt-farm: {named[0]}: not in a farm task")
        return result
    gridrt = resolve_gridrt(spec["gridrt"])
    if gridrt is None:
        result.update(code=1, message=f"gridrt-farm: no gridrt on {result['worker']}")
        return result
    work = tempfile.mkdtemp(prefix="gridrt-farm-task-")
    try:
        argv = [gridrt]
        shown_as = None
        if isinstance(scene, dict):
            try:
                shown_as = scene_on_this_machine(scene)
            except ValueError as e:
                result.update(code=2, message=f"gridrt-farm: {e}")
                return result
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
            result.update(code=1, message=f"gridrt-farm: cannot run '{gridrt}' on "
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
