"""What the farm tells the user: a progress bar on a terminal (tasks and frames done,
workers alive, time left) redrawn at most twice a second and once more when every task is
done, and the closing summary."""
import sys
import time

from .build_check import short

BAR_WIDTH = 24
REDRAW_SECONDS = 0.5


class Progress:
    def __init__(self, tasks, frames, quiet, stream=sys.stderr):
        self.tasks, self.frames = tasks, frames
        self.stream = stream
        self.shown = not quiet and stream.isatty()
        self.started = time.monotonic()
        self.last_draw = 0.0

    def update(self, tasks_done, frames_done, workers, force=False):
        if not self.shown:
            return
        now = time.monotonic()
        finished = tasks_done >= self.tasks  # the full bar is always drawn once
        if not force and not finished and now - self.last_draw < REDRAW_SECONDS:
            return
        self.last_draw = now
        share = tasks_done / self.tasks if self.tasks else 1.0
        filled = int(round(share * BAR_WIDTH))
        elapsed = now - self.started
        left = f"{elapsed / share - elapsed:.0f} s left" if share > 0 else "time left unknown"
        self.stream.write(f"\r[{'#' * filled}{'.' * (BAR_WIDTH - filled)}] tasks "
                          f"{tasks_done}/{self.tasks}, frames {frames_done}/{self.frames}, "
                          f"{workers} workers, {left}   ")
        self.stream.flush()

    def close(self):
        if self.shown:
            self.stream.write("\r\033[K")
            self.stream.flush()


def summary_line(stats):
    """One line: tasks, retries, lost workers, frames, time and the cluster's ray rate."""
    seconds = stats["seconds"]
    rate = stats["rays"] / seconds / 1e6 if seconds > 0 else 0.0
    kept = f", {stats['frames_kept']} kept" if stats["frames_kept"] else ""
    build = f" by gridrt {stats['gridrt_version']} build {short(stats['build'])}" \
        if stats.get("build") else ""
    left = len(stats.get("workers_left_out") or {})
    return (f"gridrt-farm: {stats['frames_written']} frame(s) written{kept}, "
            f"{stats['tasks']} tasks ({stats['retries']} retried, {stats['workers_lost']} "
            f"workers lost, {left} left out) on {stats['workers_seen']} workers{build} in "
            f"{seconds:.2f} s, {rate:.3g} Mrays/s across the cluster -> {stats['output']}")
