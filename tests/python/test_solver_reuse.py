"""numerics.solver: reuse on the phase field and the flow (docs/scenes.md): the factors of
an earlier matrix precondition GMRES (relative residual 1e-10) until a solve needs more
than 8 iterations. The observables equal the direct solves' to the residual, with a
fraction of the factorisations, and the iteration counts are observables columns
(phase_field_krylov_iterations, flow_krylov_iterations: per row; *_factorisations: so far).
The reaction-diffusion species are covered in test_gtpase.py."""
import sys
from pathlib import Path

import pytest

from conftest import run_scene

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_checkpoint import vesicle_scene  # noqa: E402
from test_rising_bubble import bubble_scene  # noqa: E402


def direct_and_reuse(scene, tmp_path):
    runs = {}
    for solver in ("direct", "reuse"):
        s = dict(scene, numerics=dict(scene["numerics"], solver=solver), output={})
        (tmp_path / solver).mkdir()
        runs[solver] = run_scene(s, tmp_path / solver)
    return runs["direct"], runs["reuse"]


def largest_difference(direct, reuse, key):
    return max(abs(a - b) / max(1.0, abs(a)) for a, b in zip(direct[key], reuse[key]))


# scene, (observable, bound on its difference from direct), the sub-problems' column prefixes,
# the bound on the GMRES iterations of one step
CASES = {
    # Cahn-Hilliard and Navier-Stokes (Re 100, ratios 0.1): both matrices change every step.
    # Seen: differences 2e-11 (rise velocity), 7e-12, 1e-12, 3e-12; 4 factorisations each
    # in 20 steps (one per mesh: it remeshes every 5 steps); 4-6 iterations per step.
    "bubble": (bubble_scene(0.2), {"rise_velocity": 1e-9, "center_y": 1e-9, "volume": 1e-10,
                                   "energy_ch": 1e-9},
               ("phase_field", "flow"), 8),
    # The L2 Helfrich vesicle with its multipliers: three solves a step (the state and the
    # two unit loads). Seen: 5e-9 (Helfrich energy), 2e-14 (volume), 9e-14 (surface); 14
    # factorisations in 40 steps; 12-17 iterations per step, i.e. 4-6 per solve.
    "vesicle": (vesicle_scene(), {"helfrich_energy": 1e-7, "volume": 1e-12, "surface": 1e-12,
                                  "center_x": 1e-10},
                ("phase_field",), 3 * 8),
}


@pytest.mark.parametrize("case", list(CASES))
def test_reused_factorisations_give_the_direct_solves_observables(tmp_path, case):
    scene, bounds, prefixes, per_step = CASES[case]
    direct, reuse = direct_and_reuse(scene, tmp_path)
    for key, bound in bounds.items():
        diff = largest_difference(direct, reuse, key)
        print(f"{case} {key}: reuse against direct {diff:.1e}")
        assert diff < bound, key
    steps = len(reuse["step"]) - 1
    for prefix in prefixes:
        factorisations = reuse[f"{prefix}_factorisations"][-1]
        iterations = reuse[f"{prefix}_krylov_iterations"][1:]
        print(f"{case} {prefix}: {factorisations:.0f} factorisations in {steps} steps, "
              f"GMRES iterations per step {[int(i) for i in iterations]}")
        assert factorisations <= steps / 2.5
        assert max(iterations) <= per_step
    # direct has no such columns: its counts are in the run's last line only
    assert not any(k.endswith("_krylov_iterations") for k in direct)


def test_flow_solver_reuses_the_flows_factors_alone(tmp_path):
    # flow.solver: reuse with numerics.solver: direct: the flow keeps its factors, the phase
    # field factorises every step. The observables equal the direct run's as above.
    scene = dict(bubble_scene(0.2), output={})
    runs = {}
    for name, flow in (("direct", scene["flow"]), ("flow-reuse", dict(scene["flow"], solver="reuse"))):
        (tmp_path / name).mkdir()
        runs[name] = run_scene(dict(scene, flow=flow), tmp_path / name)
    direct, flow_only = runs["direct"], runs["flow-reuse"]
    for key, bound in CASES["bubble"][1].items():
        diff = largest_difference(direct, flow_only, key)
        print(f"flow.solver reuse {key}: against direct {diff:.1e}")
        assert diff < bound, key
    steps = len(flow_only["step"]) - 1
    assert flow_only["flow_factorisations"][-1] <= steps / 2.5
    assert max(flow_only["flow_krylov_iterations"][1:]) <= 8
    assert not any(k.startswith("phase_field_") and k.endswith("_krylov_iterations")
                   for k in flow_only)
