"""With a CPU to spare, the phase-field step assembles its unit loads beside the right-hand
side and its area linearisation beside the solve, on a second thread. Each vector is still
assembled by one thread in the same order, so the observables are bitwise those of one
thread. OpenBLAS runs on one thread in both runs: its threads would change the round-off of
the factorisation."""
import os

import pytest

from conftest import circle_scene, run_scene

COLUMNS = ("volume", "surface", "helfrich_energy", "total_energy", "center_x", "circularity")


@pytest.mark.parametrize("linearisation", ["stabilised", "taylor"])
def test_second_thread_changes_no_digit(tmp_path, linearisation):
    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip("one CPU: the second thread is never used")
    scene = circle_scene("helfrich_lagrange", epsilon=0.08, end_time=0.02, dt=1e-3,
                         linearisation=linearisation)
    scene["cells"] = [{"shape": "ellipse", "center": [0.1, 0], "semi_axes": [1.2, 0.7]}]
    scene["numerics"]["mesh"]["remesh_every"] = 10
    runs, logs = {}, []
    for threads in (1, 2):
        (tmp_path / str(threads)).mkdir()
        runs[threads] = run_scene(scene, tmp_path / str(threads), log=logs,
                                  env={"OMP_NUM_THREADS": str(threads),
                                       "OPENBLAS_NUM_THREADS": "1"})
    assert "1 assembly thread per rank" in logs[0]
    assert "2 assembly threads per rank" in logs[1]
    assert len(runs[1]["time"]) == len(runs[2]["time"]) == 21
    for key in COLUMNS:
        assert runs[1][key] == runs[2][key], f"{key} differs with a second thread"
