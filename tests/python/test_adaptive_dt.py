"""Adaptive time step (numerics.adaptive_dt, docs/scenes.md "Adaptive time step"): each step's
local error is estimated from the extrapolation of phi^n and phi^{n-1}; a step beyond the
tolerance is rejected and repeated from the saved state with a smaller step, and the next
step follows the estimate. The relaxing ellipse (L2 Helfrich flow, no flow field) on a fixed
mesh against a small-step BDF2 reference; a restart continues the step sequence bit for bit."""

import pytest

from conftest import circle_scene, run_scene
from test_checkpoint import assert_same_observables, run_and_restart

END = 0.05
REFERENCE_STEPS = 512  # BDF2 at END/512: error ~3e-7, 20x below the tightest run's


def relaxing_ellipse(dt, scheme="bdf2", tolerance=None, **numerics):
    scene = circle_scene("helfrich_lagrange", epsilon=0.08, end_time=END, dt=dt,
                         time_scheme=scheme, **numerics)
    scene["cells"] = [{"shape": "ellipse", "center": [0, 0], "semi_axes": [1.2, 0.7]}]
    if tolerance:
        scene["numerics"]["adaptive_dt"] = {"tolerance": tolerance}
    return scene


def run(scene, workdir):
    workdir.mkdir()
    return run_scene(scene, workdir)


def test_bdf2_with_adaptive_steps_meets_tighter_tolerances_and_beats_uniform_steps(tmp_path):
    """Tolerances 1e-2, 1e-3, 1e-4 from a first step of 1e-5. Seen: 15, 26, 63 steps;
    Helfrich-energy errors 6.6e-5, 3.3e-5, 5.9e-6 against uniform BDF2 with as many steps
    2.8e-4, 1.0e-4, 1.9e-5 (the steps go where phi changes fast: the first relaxation)."""
    reference = run(relaxing_ellipse(END / REFERENCE_STEPS), tmp_path / "reference")
    exact = reference["helfrich_energy"][-1]
    errors = []
    for k, tolerance in enumerate((1e-2, 1e-3, 1e-4)):
        obs = run(relaxing_ellipse(1e-5, tolerance=tolerance), tmp_path / f"adaptive{k}")
        steps = len(obs["step"]) - 1
        assert obs["time"][-1] == pytest.approx(END, abs=1e-12)
        assert sum(obs["dt"]) == pytest.approx(END, rel=1e-12)
        # Every accepted step met the tolerance (the first has no estimate: -1).
        assert obs["time_error"][1] == -1
        assert max(obs["time_error"][2:]) <= tolerance
        uniform = run(relaxing_ellipse(END / steps), tmp_path / f"uniform{k}")
        error = abs(obs["helfrich_energy"][-1] - exact)
        uniform_error = abs(uniform["helfrich_energy"][-1] - exact)
        print(f"tolerance {tolerance:g}: {steps} steps ({obs['rejected_steps'][-1]:g} "
              f"rejected), error {error:.2e}; uniform steps {uniform_error:.2e}")
        assert error < uniform_error
        errors.append(error)
    assert errors[0] > errors[1] > errors[2]


def test_a_step_beyond_the_tolerance_is_rejected_and_repeated(tmp_path):
    """A first step of 1e-3 in the steep first relaxation: the second step's estimate is
    beyond 1e-3, it is taken again from the saved state, smaller (seen: 5.4e-4)."""
    obs = run(relaxing_ellipse(1e-3, tolerance=1e-3), tmp_path / "run")
    rejected = obs["rejected_steps"]
    assert rejected[1] == 0 and rejected[2] >= 1, rejected[:4]
    assert obs["dt"][2] < obs["dt"][1]
    assert obs["time_error"][2] <= 1e-3
    # The repeated step starts from the state of step 1, not from the rejected one: its
    # volume (held by the multiplier to round-off) is the volume of every other row.
    assert max(obs["volume"]) - min(obs["volume"]) < 1e-10 * obs["volume"][0]


def test_adaptive_restart_continues_the_step_sequence_bit_for_bit(tmp_path):
    """Run with checkpoints every 4 steps and remeshes every 3; restart the copy of its
    output from the checkpoint of step 12 (the newer ones removed): the rows after it,
    steps and step sizes included, are those of the run in one go."""
    scene = relaxing_ellipse(1e-4, tolerance=1e-3)
    scene["numerics"]["mesh"]["remesh_every"] = 3
    a, b = run_and_restart(scene, tmp_path, restart_step=12)
    assert len(a) > 16
    assert_same_observables(a, b)
