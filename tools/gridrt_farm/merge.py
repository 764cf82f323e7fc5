"""A frame's tiles merged into its output by gridrt-merge-tiles: EXR/TIFF as exact floats,
PNG/JPEG encoded once, after the merge, by gridrt's own image writer, so the file is what
one gridrt process writes. The tiles wait in a hidden folder beside the output, removed
once the frame is written or the job fails."""
import os
import shutil
import subprocess
import tempfile


class MergeError(Exception):
    """gridrt-merge-tiles failed: its one-line message, exit 1."""


class FrameTiles:
    """The finished tiles of one frame, as files beside its output."""

    def __init__(self, output, count):
        self.output, self.count = output, count
        self.folder = None  # made with the first tile
        self.done = set()

    def add(self, index, data):
        if self.folder is None:
            self.folder = tempfile.mkdtemp(prefix="." + os.path.basename(self.output) +
                                           ".tiles-", dir=os.path.dirname(self.output) or ".")
        with open(os.path.join(self.folder, f"tile_{index:06d}.exr"), "wb") as f:
            f.write(data)
        self.done.add(index)

    def complete(self):
        return len(self.done) == self.count

    def merge(self, merge_tiles):
        tiles = [os.path.join(self.folder, f"tile_{k:06d}.exr") for k in sorted(self.done)]
        proc = subprocess.run([merge_tiles, self.output, *tiles], capture_output=True,
                              text=True)
        self.discard()
        if proc.returncode != 0:
            lines = [l for l in proc.stderr.splitlines() if l.strip()]
            raise MergeError(lines[-1] if lines else f"gridrt-merge-tiles exited {proc.returncode}")

    def discard(self):
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None
