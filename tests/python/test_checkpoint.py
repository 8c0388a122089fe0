"""Checkpoints, restart, signals and numerical failure (issue: reliability).

A run interrupted (SIGTERM, SIGKILL, or simply an earlier end time) and restarted from its
checkpoint must give the observables of the uninterrupted run: bit for bit on the same
number of ranks (the checkpoint holds the mesh, as its refined cells, and every field
exactly), and to round-off when 2 ranks are restarted on 1 (the LU factorisation sums in
another order; test_parallel.py measures below 1e-8 relative after 30 steps)."""
import copy
import csv
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from conftest import EXE, circle_scene, mpirun_prefix, require_exe

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import cellphase_results  # noqa: E402

# Wall times and the round-off of the remesh volume correction are not part of the state.
NOT_STATE = {"wall_assembly", "wall_factorise", "wall_solve", "wall_remesh", "wall_output",
             "remesh_volume_change", "wall_flow", "wall_rd", "wall_polar",
             # numerics.solver: reuse counts (a restart starts with a new factorisation)
             "phase_field_factorisations", "phase_field_krylov_iterations",
             "flow_factorisations", "flow_krylov_iterations", "rd_factorisations",
             "rd_krylov_iterations", "polar_factorisations", "polar_krylov_iterations"}
STEPS = 40


def vesicle_scene(end_time=STEPS * 1e-3, **output):
    scene = circle_scene("helfrich_lagrange", epsilon=0.08, end_time=end_time, dt=1e-3)
    scene["cells"] = [{"shape": "ellipse", "center": [0.1, 0], "semi_axes": [1.2, 0.7]}]
    scene["numerics"]["mesh"]["remesh_every"] = 3
    scene["output"] = {"every": 2, "progress": False, "checkpoints": {"every": 4, "keep": 3},
                       **output}
    return scene


def write_scene(scene, workdir, run_dir):
    scene = dict(scene, output=dict(scene["output"], directory=str(run_dir)))
    path = workdir / f"{run_dir.name}.yaml"
    path.write_text(yaml.safe_dump(scene))
    return path


def cellphase(args, ranks=1, timeout=600):
    require_exe()
    return subprocess.run(mpirun_prefix(ranks) + [EXE, *map(str, args)], capture_output=True,
                          text=True, timeout=timeout)


def rows(run_dir):
    with open(run_dir / "observables.csv") as f:
        return list(csv.DictReader(f))


def restart_from_shorter_run(full_scene, part_scene, tmp_path):
    """Runs full_scene in one go and part_scene (the same scene ending earlier), then
    continues full_scene from the newest checkpoint of the shorter run. Returns the rows of
    the run in one go, those of the continued run, and the restart's stdout."""
    full_dir, part_dir = tmp_path / "full", tmp_path / "part"
    full = write_scene(full_scene, tmp_path, full_dir)
    part = write_scene(part_scene, tmp_path, part_dir)
    assert cellphase(["run", full]).returncode == 0
    assert cellphase(["run", part]).returncode == 0
    proc = cellphase(["run", full, "--restart", part_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return rows(full_dir), rows(part_dir), proc.stdout


def run_and_restart(scene, tmp_path, restart_step):
    """The scene in one go with checkpoints every 4 steps, then a copy of its output
    continued from the checkpoint of restart_step (the newer ones removed). Returns the
    observables' rows of both."""
    scene = copy.deepcopy(scene)
    scene["output"] = {"every": 0, "progress": False, "checkpoints": {"every": 4, "keep": 100}}
    full_dir, part_dir = tmp_path / "full", tmp_path / "part"
    proc = cellphase(["run", write_scene(scene, tmp_path, full_dir)])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    shutil.copytree(full_dir, part_dir)
    for checkpoint in (part_dir / "checkpoints").glob("checkpoint-*.cpk"):
        if int(checkpoint.stem.split("-")[1]) > restart_step:
            checkpoint.unlink()
    proc = cellphase(["run", write_scene(scene, tmp_path, part_dir), "--restart", part_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"(step {restart_step}," in proc.stdout
    return rows(full_dir), rows(part_dir)


def assert_same_observables(a, b, rel=0.0):
    assert [r["step"] for r in a] == [r["step"] for r in b]
    for ra, rb in zip(a, b):
        for key in ra:
            if key in NOT_STATE:
                continue
            x, y = float(ra[key]), float(rb[key])
            assert abs(x - y) <= rel * max(abs(x), 1.0), f"step {ra['step']}, {key}: {x} vs {y}"


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """The reference: the scene run in one go, serial."""
    work = tmp_path_factory.mktemp("reference")
    run_dir = work / "full"
    proc = cellphase(["run", write_scene(vesicle_scene(), work, run_dir)])
    assert proc.returncode == 0, proc.stderr
    return rows(run_dir)


def start_and_stop(scene_path, run_dir, sig, after_rows, ranks=1):
    """Start a run and send `sig` once observables.csv has `after_rows` steps."""
    proc = subprocess.Popen(mpirun_prefix(ranks) + [EXE, "run", str(scene_path)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    csv_path = run_dir / "observables.csv"
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None:
        if csv_path.exists() and csv_path.read_text().count("\n") > after_rows:
            break
        time.sleep(0.02)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=300)
    return proc.returncode, out, err


def test_sigterm_stops_with_checkpoint_and_restart_equals_uninterrupted(tmp_path, uninterrupted):
    require_exe()
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(), tmp_path, run_dir)
    code, out, err = start_and_stop(scene_path, run_dir, signal.SIGTERM, after_rows=6)
    assert code == 5, out + err
    assert "stopped by SIGTERM" in out and "Traceback" not in err
    stopped_at = int(re.search(r"after step (\d+)", out).group(1))
    assert 5 <= stopped_at < STEPS
    # The printed command continues the run.
    command = re.search(r"Continue with:\n\s+(.*)", out).group(1).split()
    assert command[:2] == ["cellphase", "run"] and "--restart" in command
    proc = cellphase(command[1:])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"restarting from {run_dir}/checkpoints/checkpoint-{stopped_at:08d}.cpk" in proc.stdout
    assert_same_observables(uninterrupted, rows(run_dir))  # bit for bit


@pytest.mark.parametrize("output_format", ["xdmf", "vtk"])
def test_sigkill_leaves_readable_output_and_a_valid_checkpoint(tmp_path, uninterrupted,
                                                               output_format):
    require_exe()
    run_dir = tmp_path / "run"
    # Fields at every step: the kill is likely to hit a write.
    scene_path = write_scene(vesicle_scene(every=1, format=output_format), tmp_path, run_dir)
    code, _, _ = start_and_stop(scene_path, run_dir, signal.SIGKILL, after_rows=9)
    assert code == -signal.SIGKILL
    observed = cellphase_results.read_observables(run_dir)
    written = list(cellphase_results.read_fields(run_dir))
    assert len(observed["time"]) >= 9 and len(written) >= 8
    for _, points, cells, values in written:
        assert abs(values["phi"]).max() < 1.2 and len(points) > 0 and len(cells) > 0
    proc = cellphase(["run", scene_path, "--restart", run_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert_same_observables(uninterrupted, rows(run_dir))
    times = [t for t, *_ in cellphase_results.read_fields(run_dir)]
    assert times == sorted(times) and len(times) == STEPS + 1  # the index was cut back and continued


def test_truncated_checkpoint_is_skipped_for_the_previous_one(tmp_path, uninterrupted):
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(), tmp_path, run_dir)
    assert cellphase(["run", scene_path]).returncode == 0
    checkpoints = sorted((run_dir / "checkpoints").glob("checkpoint-*.cpk"))
    assert [c.name for c in checkpoints] == [f"checkpoint-{s:08d}.cpk" for s in (32, 36, 40)]
    newest = checkpoints[-1]
    newest.write_bytes(newest.read_bytes()[: newest.stat().st_size // 2])
    proc = cellphase(["run", scene_path, "--restart", run_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"skipping checkpoint {newest}: truncated" in proc.stdout
    assert "restarting from" in proc.stdout and "checkpoint-00000036.cpk (step 36" in proc.stdout
    assert_same_observables(uninterrupted, rows(run_dir))


def test_two_ranks_stopped_by_sigusr1_restarted_on_one(tmp_path):
    """2 ranks stopped through mpirun (which forwards SIGUSR1 to every rank), then 1 rank
    to the end, against 2 ranks in one go."""
    full_dir, part_dir = tmp_path / "full", tmp_path / "part"
    full_path = write_scene(vesicle_scene(), tmp_path, full_dir)
    part_path = write_scene(vesicle_scene(), tmp_path, part_dir)
    assert cellphase(["run", full_path], ranks=2).returncode == 0
    code, out, err = start_and_stop(part_path, part_dir, signal.SIGUSR1, after_rows=8, ranks=2)
    assert code == 5 and "stopped by SIGUSR1" in out, out + err
    proc = cellphase(["run", part_path, "--restart", part_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "restarting from" in proc.stdout
    a, b = rows(full_dir), rows(part_dir)
    assert [r["dofs"] for r in a] == [r["dofs"] for r in b]  # the same meshes
    assert_same_observables(a, b, rel=1e-9)


def test_far_too_large_time_step_stops_with_last_good_state(tmp_path):
    """Allen-Cahn at 150x the demo's dt: the linearised step overshoots phi to about -5.7."""
    scene = circle_scene("allen_cahn", epsilon=0.04, end_time=1.2, dt=0.3)
    scene["phase_field"]["mobility"] = 25
    scene["output"] = {"every": 1, "progress": False}
    run_dir = tmp_path / "run"
    scene_path = write_scene(scene, tmp_path, run_dir)
    proc = cellphase(["run", scene_path])
    assert proc.returncode == 3, proc.stdout + proc.stderr
    message = proc.stderr
    assert "numerical failure in the phase-field module (allen_cahn) at step 1, t = 0.3" in message
    assert "numerics.limits.phi_bound" in message and "last good state (step 0, t = 0)" in message
    assert "Traceback" not in message and "PETSC ERROR" not in message
    # The last good state is readable: fields, observables and a checkpoint to restart from.
    (time0, _, _, values), = list(cellphase_results.read_fields(run_dir))
    assert time0 == 0 and abs(values["phi"]).max() <= 1 + 1e-12  # the initial tanh profile
    assert len(cellphase_results.read_observables(run_dir)["time"]) == 1
    proc = cellphase(["run", scene_path, "--restart", run_dir, "--set", "numerics.dt=0.05",
                      "--set", "numerics.end_time=0.1"])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "restarting from" in proc.stdout and "(step 0, t = 0)" in proc.stdout


def test_restart_with_a_smaller_time_step_counts_its_steps_from_the_restored_time(tmp_path):
    """A run to t = 0.02 at dt 1e-3 continued to t = 0.03 at dt 5e-4: 20 more steps ending
    exactly at 0.03. (The count used to be end_time / dt from t = 0, 60 steps: after 20 the
    run went on with steps of round-off size, whose system MUMPS could not factorise.)"""
    scene = vesicle_scene(end_time=0.02)
    run_dir = tmp_path / "run"
    scene_path = write_scene(scene, tmp_path, run_dir)
    assert cellphase(["run", scene_path]).returncode == 0
    proc = cellphase(["run", scene_path, "--restart", run_dir, "--set", "numerics.dt=5e-4",
                      "--set", "numerics.end_time=0.03"])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    steps = [(int(r["step"]), float(r["time"])) for r in rows(run_dir)]
    assert steps[-1][0] == 40 and steps[-1][1] == 0.03
    assert all(abs((t1 - t0) - 5e-4) < 1e-12 for (_, t0), (_, t1) in zip(steps[20:], steps[21:]))


def test_restart_whose_observables_have_other_columns_rewrites_them_by_name(tmp_path):
    """observables.csv written by a run with other columns (an older version, another scene)
    is continued under the new header: the kept rows by column name, nan where they have
    none, with a note on stderr; nothing is shifted into the wrong column."""
    scene = vesicle_scene(end_time=0.008)
    run_dir = tmp_path / "run"
    scene_path = write_scene(scene, tmp_path, run_dir)
    assert cellphase(["run", scene_path]).returncode == 0
    before = rows(run_dir)
    # As if written by a version without `circularity` and with a column since removed.
    path = run_dir / "observables.csv"
    names = list(before[0])
    old = [n for n in names if n != "circularity"] + ["retired"]
    path.write_text(",".join(old) + "\n" + "".join(
        ",".join(r[n] if n != "retired" else "7" for n in old) + "\n" for r in before))
    proc = cellphase(["run", scene_path, "--restart", run_dir, "--set",
                      "numerics.end_time=0.012"])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "added circularity" in proc.stderr and "dropped retired" in proc.stderr, proc.stderr
    after = rows(run_dir)
    assert list(after[0]) == names
    assert [r["step"] for r in after] == [str(s) for s in range(13)]
    for r, b in zip(after[:9], before):
        assert r["circularity"] == "nan"
        assert all(r[n] == b[n] for n in names if n != "circularity")
    assert all(float(r["circularity"]) > 0.5 for r in after[9:])


def test_volume_drift_beyond_the_scene_limit_stops(tmp_path):
    scene = circle_scene("allen_cahn_volume", end_time=0.005)
    scene["numerics"]["limits"] = {"volume_drift": 1e-12}
    run_dir = tmp_path / "run"
    proc = cellphase(["run", write_scene(dict(scene, output={"every": 0, "progress": False}),
                                         tmp_path, run_dir)])
    assert proc.returncode == 3, proc.stdout + proc.stderr
    assert "numerics.limits.volume_drift = 1e-12" in proc.stderr
    assert "at step 1," in proc.stderr


@pytest.mark.parametrize("make_dir, expected", [
    (lambda d: d / "missing", "is not a directory"),
    (lambda d: d, "no valid checkpoint in"),
])
def test_restart_without_checkpoint_is_refused(tmp_path, make_dir, expected):
    scene_path = write_scene(vesicle_scene(), tmp_path, tmp_path / "run")
    proc = cellphase(["run", scene_path, "--restart", make_dir(tmp_path)])
    assert proc.returncode == 2 and expected in proc.stderr, proc.stderr


def bubble_flow_scene(end_time):
    """A coarse rising bubble (Navier-Stokes-Cahn-Hilliard) with remeshing every 3 steps."""
    return {
        "domain": {"lower": [0, 0], "upper": [1, 2], "resolution": [6, 12]},
        "cells": [{"shape": "circle", "center": [0.5, 0.5], "radius": 0.25}],
        "phase_field": {"model": "cahn_hilliard", "mobility": 1e-3},
        "numbers": {"Re": 100, "Ca": 0.385},
        "flow": {"density": {"inside": 0.1, "outside": 1},
                 "viscosity": {"inside": 0.1, "outside": 1}, "gravity": [0, -98],
                 "walls": {"left": "free_slip", "right": "free_slip"}},
        # dt and the end times are binary fractions, so that the last step of the shorter
        # run is not shortened by round-off (a different dt would change the flow matrix).
        "numerics": {"epsilon": 0.05, "dt": 1 / 64, "end_time": end_time,
                     "mesh": {"remesh_every": 3, "points_across_interface": 3}},
        "output": {"every": 0, "progress": False, "checkpoints": {"every": 4, "keep": 2}},
    }


def test_flow_restart_equals_uninterrupted(tmp_path):
    """The checkpoint holds v^n (and p): a coupled run to step 8 continued to step 14
    (remeshes at steps 9 and 12 after the restart) equals the run in one go bit for bit."""
    a, b, stdout = restart_from_shorter_run(bubble_flow_scene(14 / 64),
                                            bubble_flow_scene(8 / 64), tmp_path)
    assert "(step 8," in stdout
    assert float(a[-1]["kinetic_energy"]) > 0 and float(a[-1]["rise_velocity"]) > 0
    assert_same_observables(a, b)
