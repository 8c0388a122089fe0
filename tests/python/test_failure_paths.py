"""Failure and restart paths the docs promise (issue 18, item 3): a NaN in a field stops
the run with the last good state kept; Ctrl-C (SIGINT) stops after the step with a
checkpoint, a second one at once; a serial run continued on 2 ranks; a restart whose
scene changed the mesh is refused before step 1."""
import os
import signal
import subprocess
import time

from conftest import EXE, mpirun_prefix, require_exe
from test_checkpoint import (STEPS, assert_same_observables, cellphase, rows, start_and_stop,
                             uninterrupted, vesicle_scene, write_scene)  # noqa: F401 (fixture)

import cellphase_results


def test_nan_in_a_field_stops_with_the_last_good_state(tmp_path, uninterrupted):
    require_exe()
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(every=1), tmp_path, run_dir)
    proc = subprocess.run([EXE, "run", str(scene_path)], capture_output=True, text=True,
                          timeout=600, env={**os.environ, "CELLPHASE_TEST_NAN_AT_STEP": "7"})
    assert proc.returncode == 3, proc.stdout + proc.stderr
    assert "numerical failure" in proc.stderr and "at step 7," in proc.stderr
    assert "field phi is not finite (NaN or Inf)" in proc.stderr
    assert "last good state (step 6," in proc.stderr and "Traceback" not in proc.stderr
    # The output ends with the good state: fields of steps 0 to 6, all finite (step 6
    # written again on the mesh of the remesh before step 7 replaces its first entry).
    frames = list(cellphase_results.read_fields(run_dir))
    assert len(frames) == 7 and frames[-1][0] == float(rows(run_dir)[6]["time"])
    assert all(abs(values["phi"]).max() < 1.2 for *_, values in frames)
    # Its checkpoint continues the run as if nothing had happened.
    proc = cellphase(["run", scene_path, "--restart", run_dir])
    assert proc.returncode == 0 and "(step 6," in proc.stdout, proc.stdout + proc.stderr
    assert_same_observables(uninterrupted, rows(run_dir))


def test_ctrl_c_stops_after_the_step_and_a_second_one_at_once(tmp_path, uninterrupted):
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(), tmp_path, run_dir)
    code, out, err = start_and_stop(scene_path, run_dir, signal.SIGINT, after_rows=6)
    assert code == 5 and "stopped by SIGINT" in out, out + err
    assert "Traceback" not in err
    proc = cellphase(["run", scene_path, "--restart", run_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert_same_observables(uninterrupted, rows(run_dir))

    # Two Ctrl-C: the second ends the process at once (killed by SIGINT, no checkpoint of
    # its own; the run stays restartable from the checkpoints already written).
    run_dir = tmp_path / "twice"
    scene_path = write_scene(vesicle_scene(), tmp_path, run_dir)
    proc = subprocess.Popen([EXE, "run", str(scene_path)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    # Wait for the step-0 checkpoint (renamed into place whole): before it exists there is
    # nothing to restart from, and a double Ctrl-C then rightly leaves nothing behind.
    deadline = time.time() + 300
    while time.time() < deadline and not list((run_dir / "checkpoints").glob("*.cpk")):
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=300)
    assert proc.returncode in (-signal.SIGINT, 5), proc.returncode
    proc = cellphase(["run", scene_path, "--restart", run_dir])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert_same_observables(uninterrupted, rows(run_dir))


def test_serial_run_continued_on_two_ranks(tmp_path, uninterrupted):
    """1 -> 2 ranks: the mesh is rebuilt from the base mesh on 2 ranks and every field found
    again by position; the sums of the LU factorisation run in another order, so the
    observables agree to round-off (test_parallel.py measures below 1e-8 after 30 steps)."""
    mpirun_prefix(2)  # skips without mpirun
    run_dir = tmp_path / "part"
    part = write_scene(vesicle_scene(end_time=STEPS / 2 * 1e-3), tmp_path, run_dir)
    assert cellphase(["run", part]).returncode == 0
    full = write_scene(vesicle_scene(), tmp_path, run_dir)
    proc = cellphase(["run", full, "--restart", run_dir], ranks=2)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "restarting from" in proc.stdout and "(step 20," in proc.stdout
    a, b = uninterrupted, rows(run_dir)
    assert [r["dofs"] for r in a] == [r["dofs"] for r in b]  # the same meshes
    assert_same_observables(a, b, rel=1e-8)


def test_internal_error_on_one_rank_stops_every_rank(tmp_path):
    """An unexpected error on one rank alone (a bug, not a failure the program checks for
    on every rank) leaves the other rank in a collective call: the run must stop with the
    error's message instead of hanging in the destructors' collective frees."""
    prefix = mpirun_prefix(2)  # skips without mpirun
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(), tmp_path, run_dir)
    t0 = time.time()
    proc = subprocess.run(prefix + [EXE, "run", str(scene_path)], capture_output=True,
                          text=True, timeout=300,
                          env={**os.environ, "CELLPHASE_TEST_THROW_AT_STEP": "3",
                               "CELLPHASE_TEST_THROW_RANK": "1"})
    print(f"stopped in {time.time() - t0:.1f} s with status {proc.returncode}")
    assert proc.returncode != 0, proc.stdout + proc.stderr
    assert "error on rank 1: test: an internal error on this rank alone after step 3" \
        in proc.stderr, proc.stderr


def test_restart_with_another_mesh_is_refused_before_step_one(tmp_path):
    run_dir = tmp_path / "run"
    scene_path = write_scene(vesicle_scene(end_time=4e-3), tmp_path, run_dir)
    assert cellphase(["run", scene_path]).returncode == 0
    before = (run_dir / "observables.csv").read_text()
    # The base mesh moved by 0.1 (same cell size, same levels), and a finer epsilon.
    for change, message in (("domain.lower=[-2.1, -2.1]", "does not fit the scene's base mesh"),
                            ("numerics.epsilon=0.04", "refinement levels")):
        proc = cellphase(["run", scene_path, "--restart", run_dir, "--set", change])
        assert proc.returncode == 2, proc.stdout + proc.stderr
        assert proc.stderr.startswith("error: ") and message in proc.stderr, proc.stderr
        assert "Traceback" not in proc.stderr
        assert (run_dir / "observables.csv").read_text() == before  # nothing was run


def sphere_in_shear(end_time):
    """3D: an ellipsoid in a Stokes shear flow between moving walls, remeshed every 2 steps,
    a checkpoint every 3 steps."""
    return {
        "domain": {"lower": [-1.2] * 3, "upper": [1.2] * 3, "resolution": [4, 4, 4]},
        "boundary": {"phi": "neumann"},
        "cells": [{"shape": "ellipse", "center": [0, 0, 0], "semi_axes": [0.5, 0.4, 0.4]}],
        "phase_field": {"model": "helfrich_hm1", "mobility": 1e-3, "penalty_area": 100},
        "numbers": {"Be": 10.0},
        "flow": {"equations": "stokes",
                 "walls": {"bottom": {"type": "moving", "velocity": [-1, 0, 0]},
                           "top": {"type": "moving", "velocity": [1, 0, 0]}}},
        "numerics": {"epsilon": 0.2, "dt": 1 / 64, "end_time": end_time,
                     "mesh": {"remesh_every": 2, "points_across_interface": 2.5}},
        "output": {"every": 0, "progress": False, "checkpoints": {"every": 3, "keep": 2}},
    }


def test_3d_flow_run_with_remeshing_restarts_bit_for_bit(tmp_path):
    """Issue 18, item 4: a 3D run with flow and remeshes (before steps 3 and 5), continued
    from its checkpoint at step 3, equals the run in one go bit for bit."""
    from test_checkpoint import restart_from_shorter_run
    a, b, stdout = restart_from_shorter_run(sphere_in_shear(6 / 64), sphere_in_shear(3 / 64),
                                            tmp_path)
    assert "(step 3," in stdout and len(a) == 7
    assert len({r["dofs"] for r in a}) > 1  # the mesh changed at the remeshes
    assert float(a[-1]["flow_dofs"]) > 0
    assert_same_observables(a, b)
