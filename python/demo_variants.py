"""Variants of one demo scene, run side by side: the demos that compare cases of one
experiment (demos/cell-collision/run_cases.py, demos/rbc-bifurcation/run_potentials.py)
write each variant's scene next to its log and pick the output frames nearest to the
times of their figures."""
import concurrent.futures
import os
import subprocess
from pathlib import Path

import yaml

from cellphase_results import read_fields

ROOT = Path(__file__).resolve().parents[1]


def executable():
    """$CELLPHASE_EXE (a copy survives a rebuild during a long run), else build/cellphase."""
    return os.environ.get("CELLPHASE_EXE", str(ROOT / "build" / "cellphase"))


def run_variant(scene, out, name, overrides=()):
    """Write `scene` (a dict) to out/NAME.yaml, run it with `--set` overrides, the log in
    out/NAME.log; returns the exit code."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    cmd = [executable(), "run", str(path)] + [a for o in overrides for a in ("--set", o)]
    with open(out / f"{name}.log", "w") as log:
        return subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT).returncode


def run_all(variants, parallel=2):
    """variants: {name: callable returning an exit code}; yields (name, code) in order,
    `parallel` at a time."""
    with concurrent.futures.ThreadPoolExecutor(parallel) as pool:
        yield from zip(variants, pool.map(lambda run: run(), variants.values()))


def frames_at(run_dir, times, fields=None):
    """The output frames (time, points, cells, values) nearest to each wanted time (None:
    the last frame written)."""
    frames = list(read_fields(run_dir, fields=fields))
    if not frames:
        raise SystemExit(f"{run_dir}: no fields written")
    return [frames[-1] if t is None else min(frames, key=lambda f: abs(f[0] - t))
            for t in times]
