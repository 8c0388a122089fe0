"""Helpers shared by the tests that run the `cellphase` executable."""
import csv
import os
import shutil
import subprocess

import numpy as np
import pytest
import yaml

EXE = os.environ.get("CELLPHASE_EXE")


def require_exe():
    if not EXE:
        pytest.skip("CELLPHASE_EXE is not set (run the tests through ctest)")


def mpirun_prefix(ranks):
    if ranks == 1:
        return []
    launcher = shutil.which("mpirun")
    if launcher is None:
        pytest.skip("mpirun not found")
    extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return [launcher, *extra, "--oversubscribe", "-n", str(ranks)]


def run_scene(scene, workdir, ranks=1, timeout=900, env=None, log=None):
    """Write `scene` (a dict) to workdir, run it (with `env` added to the environment),
    return observables as columns; `log` (a list), if given, receives the standard output."""
    require_exe()
    scene = dict(scene)
    scene.setdefault("output", {})
    scene["output"] = {"every": 0, "progress": False, **scene["output"],
                       "directory": str(workdir / "out")}
    path = workdir / "scene.yaml"
    path.write_text(yaml.safe_dump(scene))
    proc = subprocess.run(mpirun_prefix(ranks) + [EXE, "run", str(path)], capture_output=True,
                          text=True, timeout=timeout, env={**os.environ, **(env or {})})
    assert proc.returncode == 0, f"cellphase failed:\n{proc.stdout}\n{proc.stderr}"
    if log is not None:
        log.append(proc.stdout)
    with open(workdir / "out" / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def one_rank_against_two(scene, workdir):
    """Run `scene` on one rank and on two; the largest difference of each observable (not
    the wall times) relative to max(1, |value|), and the two runs' columns."""
    (workdir / "one").mkdir()
    (workdir / "two").mkdir()
    one = run_scene(scene, workdir / "one")
    two = run_scene(scene, workdir / "two", ranks=2)
    worst = {}
    for key in one:
        if key.startswith("wall_") or key == "remesh_volume_change":
            continue
        worst[key] = max(abs(a - b) / max(1.0, abs(a)) for a, b in zip(one[key], two[key]))
    return worst, one, two


def assert_same_as_lu(runs, keys, tol=1e-9):
    """runs["default"] (the symmetric L D L^T factorisation) against runs["lu"]: the largest
    difference of each observable relative to max(1, |value|) (quantities that are 0 up to
    round-off, such as a centre at the origin, are compared absolutely) must be below tol."""
    for key in keys:
        a, b = runs["default"][key], runs["lu"][key]
        diff = max(abs(x - y) for x, y in zip(a, b)) / max([1.0] + [abs(x) for x in b])
        print(f"{key}: L D L^T against LU {diff:.1e}")
        assert diff < tol, f"{key}: L D L^T and LU differ by {diff:.2e}"


def circle_scene(model, epsilon=0.08, radius=1.0, **numerics):
    """A circle (or ellipse with semi_axes) in [-2, 2]^2 for quick runs."""
    return {
        "domain": {"lower": [-2, -2], "upper": [2, 2], "resolution": [16, 16]},
        "cells": [{"shape": "circle", "center": [0, 0], "radius": radius}],
        "phase_field": {"model": model},
        "numerics": {"epsilon": epsilon, "dt": 1e-3, "end_time": 0.01,
                     "mesh": {"remesh_every": 0, "points_across_interface": 4}, **numerics},
    }


def write_vtk_run(run_dir, points, cells, fields, earlier=()):
    """Output times in the ascii VTK layout python/cellphase_results.py reads: `fields` at
    t = 2.5, after the (time, fields) pairs of `earlier`."""
    run_dir.mkdir()
    text = lambda a: " ".join(f"{x:.17g}" for x in np.ravel(a))  # noqa: E731
    points3 = np.column_stack([points, np.zeros(len(points))])
    datasets = ""
    for k, (time, frame) in enumerate([*earlier, (2.5, fields)]):
        data = "".join(f'<DataArray Name="{name}" NumberOfComponents="{np.shape(a)[1] if np.ndim(a) > 1 else 1}" '
                       f'format="ascii">{text(a)}</DataArray>' for name, a in frame.items())
        (run_dir / f"fields_{k}.vtu").write_text(
            '<VTKFile type="UnstructuredGrid"><UnstructuredGrid>'
            f'<Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(cells)}">'
            f'<Points><DataArray NumberOfComponents="3" format="ascii">{text(points3)}</DataArray></Points>'
            f'<Cells><DataArray Name="connectivity" format="ascii">{" ".join(map(str, cells.ravel()))}</DataArray>'
            f'<DataArray Name="offsets" format="ascii">{" ".join(map(str, 3 * np.arange(1, len(cells) + 1)))}</DataArray>'
            f'<DataArray Name="types" format="ascii">{" ".join(["5"] * len(cells))}</DataArray></Cells>'
            f'<PointData>{data}</PointData></Piece></UnstructuredGrid></VTKFile>')
        datasets += f'<DataSet timestep="{time}" file="fields_{k}.vtu"/>'
    (run_dir / "fields.pvd").write_text(
        f'<VTKFile type="Collection"><Collection>{datasets}</Collection></VTKFile>')
