"""Progress of a study's running members: every INTERVAL seconds one line per running member
with its simulated time, the share of its end time done and an estimate of the time left,
read from the member's observables.csv (the members themselves run without a progress line).

    watch = ProgressWatch(interval=60)
    watch.started(name, run_dir, end_time)   # from run_member, before the run
    watch.finished(name)                     # after it
"""
import os
import threading
import time
from pathlib import Path

import yaml


def member_end_time(scene_path, overrides):
    """The member's numerics.end_time: its `set:` value, else the scene's (None if neither)."""
    try:
        if "numerics.end_time" in overrides:
            return float(overrides["numerics.end_time"])
        return float(yaml.safe_load(Path(scene_path).read_text())["numerics"]["end_time"])
    except (OSError, yaml.YAMLError, KeyError, TypeError, ValueError):
        return None


def last_time(observables):
    """The time of the last whole row of an observables.csv being written, reading only its
    head and tail; None if it has no row yet."""
    try:
        with open(observables, "rb") as f:
            header = f.readline().decode().strip().split(",")
            size = os.fstat(f.fileno()).st_size
            f.seek(max(0, size - 8192))
            tail = f.read().decode(errors="replace").split("\n")
    except OSError:
        return None
    column = header.index("time") if "time" in header else None
    rows = [r.split(",") for r in tail[:-1] if r.count(",") == len(header) - 1]
    if column is None or not rows:
        return None
    try:
        return float(rows[-1][column])
    except ValueError:
        return None


def duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"


class ProgressWatch:
    def __init__(self, interval=60.0, out=print):
        self.interval, self.out = interval, out
        # name -> (run_dir, end_time, wall at start, (wall, simulated time) when first seen)
        self.running = {}
        self.lock = threading.Lock()
        self.stop = threading.Event()
        if interval > 0:
            threading.Thread(target=self._loop, daemon=True).start()

    def started(self, name, run_dir, end_time):
        with self.lock:
            self.running[name] = (Path(run_dir), end_time, time.monotonic(), None)

    def finished(self, name):
        with self.lock:
            self.running.pop(name, None)

    def lines(self):
        """One line per running member (also used by the loop)."""
        out = []
        with self.lock:
            items = list(self.running.items())
        for name, (run_dir, end_time, wall0, first) in items:
            t = last_time(run_dir / "observables.csv")
            now = time.monotonic()
            if t is None:
                out.append(f"  {name}: starting, {duration(now - wall0)} elapsed")
                continue
            if first is None:
                # The pace is measured from here: the set-up is behind, and a member
                # continued from a checkpoint starts at the checkpoint's time.
                first = (now, t)
                with self.lock:
                    if name in self.running:
                        self.running[name] = (run_dir, end_time, wall0, first)
            line = f"  {name}: t = {t:.6g}"
            if end_time:
                line += f" of {end_time:g} ({100 * t / end_time:.0f} %)"
            line += f", {duration(now - wall0)} elapsed"
            if end_time and t > first[1]:
                pace = (now - first[0]) / (t - first[1])
                line += f", about {duration(pace * max(end_time - t, 0))} left"
            out.append(line)
        return out

    def _loop(self):
        while not self.stop.wait(self.interval):
            for line in self.lines():
                self.out(line, flush=True)
