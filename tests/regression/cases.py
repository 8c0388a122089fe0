"""The regression cases of tests/python/test_core_regression.py: every demo scene (and a few
variants that reach code paths the demos do not) cut to a handful of steps on a coarse mesh,
with a remesh and a checkpoint inside the run. Their observables were recorded with the code
before the modular core (field registry and sub-problems) replaced the hand-wired time loop;
the core must reproduce them bitwise, since it does the same arithmetic in the same order.
rbc-channel and rbc-parachute were recorded again when the Cassini oval's initial profile
became the tanh of its exact signed distance instead of the estimate f / |grad f|.

Run as a script to (re)record the baselines, all or the named ones:
    /usr/bin/python3 tests/regression/cases.py EXE [NAME ...]
"""
import copy
import csv
import pathlib
import subprocess
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent

# Columns that measure the machine, not the physics.
TIMING = {"wall_assembly", "wall_factorise", "wall_solve", "wall_remesh", "wall_output",
          "wall_flow"}


def demo(name):
    return yaml.safe_load((ROOT / "demos" / name / "scene.yaml").read_text())


def short(scene, steps=4, remesh_every=2, resolution=None):
    """The scene cut to `steps` steps with a remesh every `remesh_every` steps."""
    s = copy.deepcopy(scene)
    nu = s.setdefault("numerics", {})
    nu["end_time"] = steps * nu.get("dt", 1e-3)
    nu.setdefault("mesh", {})["remesh_every"] = remesh_every
    if resolution is not None:
        s["domain"]["resolution"] = resolution
    return s


def cases():
    c = {}
    for name in ["allen-cahn-circle", "vesicle-relaxation", "vesicle-shear",
                 "vesicle-tank-treading", "rbc-channel", "rbc-parachute",
                 "rising-bubble-case1", "rising-bubble-case2"]:
        c[name] = short(demo(name))
    # Stabilised (constant-matrix) scheme, L D L^T path
    s = short(demo("vesicle-relaxation"), steps=6)
    s["numerics"]["linearisation"] = "stabilised"
    c["vesicle-stabilised"] = s
    # Helfrich H^-1 flow with the area penalty
    s = short(demo("vesicle-relaxation"))
    s["phase_field"] = {"model": "helfrich_hm1", "mobility": 1.0, "penalty_area": 100}
    s["boundary"] = {"phi": "neumann"}
    c["vesicle-hm1"] = s
    # Inextensibility with the membrane concentration (3.70)-(3.72)
    s = short(demo("vesicle-shear"))
    s["flow"]["inextensibility"] = {"xi": 1.0, "concentration": {"penalty": 1.0,
                                                                 "diffusion": 1e-3}}
    c["vesicle-shear-concentration"] = s
    return c


def physics_columns(path):
    """Rows of observables.csv without the timing columns, as strings."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in r.items() if k not in TIMING} for r in rows]


def run_case(exe, scene, workdir, env=None):
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    s = copy.deepcopy(scene)
    s["output"] = {**s.get("output", {}), "directory": str(workdir / "out"), "every": 2,
                   "progress": False, "checkpoints": {"every": 3, "keep": 2}}
    path = workdir / "scene.yaml"
    path.write_text(yaml.safe_dump(s))
    proc = subprocess.run([exe, "run", str(path)], capture_output=True, text=True,
                          timeout=900, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"cellphase failed on {path}:\n{proc.stdout}\n{proc.stderr}")
    return workdir / "out" / "observables.csv"


if __name__ == "__main__":
    import tempfile
    exe, names = sys.argv[1], sys.argv[2:]
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene in cases().items():
            if names and name not in names:
                continue
            out = run_case(exe, scene, pathlib.Path(tmp) / name)
            rows = physics_columns(out)
            with open(HERE / f"{name}.csv", "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=list(rows[0]))
                w.writeheader()
                w.writerows(rows)
            print(f"{name}: {len(rows)} rows")
