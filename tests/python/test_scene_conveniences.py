"""Scene conveniences for a standard problem (the Cahn-Hilliard problem of the FEniCSx demo:
unit square, natural boundary conditions, a smooth field filling the domain, uniform mesh):
a phase crossing the boundary, the uniform-mesh switch, phi0 as a formula, the final state
written with output.every = 0, checkpoints switched off, the DOF estimate of `check` and
its warning for the stabilised scheme."""
import copy
import re
import subprocess

import pytest
import yaml

from conftest import EXE, require_exe, run_scene

SQUARE = {
    "domain": {"lower": [0, 0], "upper": [1, 1], "resolution": [24, 24]},
    "cells": [{"shape": "field", "phi0": "x*y - 0.25"}],
    "phase_field": {"model": "cahn_hilliard", "mobility": 1.0},
    # the natural condition, which lets the field cross the boundary
    "boundary": {"phi": "neumann", "contact_angle": 90},
    "numerics": {"epsilon": 0.02, "dt": 1e-5, "end_time": 2e-5, "mesh": {"adaptive": False}},
}


def p2_dofs_crossed(n):
    """P2 nodes of the n x n square split into four triangles each (crossed diagonals)."""
    vertices = (n + 1) ** 2 + n ** 2
    edges = vertices + 4 * n * n - 1  # Euler: V - E + F = 1 with F = 4 n^2 triangles
    return vertices + edges


def check(tmp_path, scene):
    require_exe()
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene))
    return subprocess.run([EXE, "check", str(path)], capture_output=True, text=True, timeout=60)


def test_uniform_switch_gives_the_uniform_mesh_and_phi0_formula_is_exact(tmp_path):
    obs = run_scene(SQUARE, tmp_path)
    # Two P2 fields (phi, mu) on the 24 x 24 crossed base mesh, never refined.
    assert obs["dofs"] == [2 * p2_dofs_crossed(24)] * 3
    # x y - 0.25 is quadratic: its P2 interpolant is exact, so int (1 + phi)/2 = 1/2 and the
    # extremes -0.25 and 0.75 (at the corners) are the formula's.
    assert abs(obs["volume"][0] - 0.5) < 1e-12
    assert abs(obs["phi_min"][0] + 0.25) < 1e-14 and abs(obs["phi_max"][0] - 0.75) < 1e-14
    # Cahn-Hilliard keeps int phi (natural conditions).
    assert max(abs(v - 0.5) for v in obs["volume"]) < 1e-12


def test_a_phase_crossing_the_boundary_runs_under_natural_conditions(tmp_path):
    # contact_angle: 90 is the natural condition of boundary.phi: neumann (grad phi . n = 0).
    scene = copy.deepcopy(SQUARE)
    scene["cells"] = [{"shape": "circle", "center": [0.0, 0.5], "radius": 0.3}]
    obs = run_scene(scene, tmp_path)
    v = obs["volume"]
    # Half a disc of radius 0.3 inside the square (the diffuse profile adds O(eps^2)).
    assert abs(v[0] - 3.14159265 * 0.09 / 2) < 5e-3
    assert max(abs(x - v[0]) for x in v) < 1e-12
    # Without the contact angle it is refused, and the message names the way.
    scene["boundary"] = {"phi": "neumann"}
    proc = check(tmp_path, scene)
    assert proc.returncode == 2
    assert "extends outside the domain" in proc.stderr
    assert "boundary.contact_angle (90 is the natural condition" in proc.stderr


def test_every_zero_writes_the_final_state_and_checkpoints_can_be_switched_off(tmp_path):
    scene = copy.deepcopy(SQUARE)
    scene["output"] = {"checkpoints": {"every": 0}}
    run_scene(scene, tmp_path)  # output.every = 0 (run_scene's default)
    out = tmp_path / "out"
    import sys
    sys.path.insert(0, str(__import__("pathlib").Path(__file__).parents[2] / "python"))
    from cellphase_results import read_fields
    frames = list(read_fields(out))
    assert [round(f[0], 12) for f in frames] == [2e-5]  # the final state only
    assert not (out / "checkpoints").exists()


def test_adaptive_false_refuses_refinement_keys(tmp_path):
    scene = copy.deepcopy(SQUARE)
    scene["numerics"]["mesh"]["remesh_every"] = 5
    proc = check(tmp_path, scene)
    assert proc.returncode == 2
    assert "numerics.mesh.remesh_every" in proc.stderr and "adaptive: false" in proc.stderr


@pytest.mark.parametrize("cell, epsilon", [
    ({"shape": "circle", "center": [0.5, 0.5], "radius": 0.3}, 0.005),
    # A field with |phi| < 0.9 nearly everywhere: the "band" is the whole square, and the
    # estimate from the interface size alone (117 x the band width) exceeded the uniform mesh.
    ({"shape": "field", "phi0": "0.3*cos(6.2832*x)*cos(6.2832*y) + 0.2*sin(9.42*x + 3.1*y)"}, 0.01),
])
def test_dof_estimate_is_at_most_the_uniform_finest_mesh(tmp_path, cell, epsilon):
    scene = copy.deepcopy(SQUARE)
    scene["cells"] = [cell]
    scene["numerics"]["epsilon"] = epsilon
    scene["numerics"]["mesh"] = {"points_across_interface": 6}
    proc = check(tmp_path, scene)
    assert proc.returncode == 0, proc.stderr
    levels = int(re.search(r"refinement levels\s+(\d+)", proc.stdout).group(1))
    estimate = float(re.search(r"degrees of freedom\s+~(\S+)", proc.stdout).group(1))
    uniform = 2 * p2_dofs_crossed(24 * 2 ** levels)
    print(f"eps {epsilon}: {levels} levels, estimate {estimate:.3g}, uniform {uniform}")
    assert estimate <= uniform


def test_check_warns_about_the_stabilised_scheme_far_outside_its_guide(tmp_path):
    scene = copy.deepcopy(SQUARE)
    scene["numerics"].update(linearisation="stabilised", dt=1e-4, epsilon=0.05, end_time=0.01)
    proc = check(tmp_path, scene)
    assert proc.returncode == 0, proc.stderr
    assert "warning: S gamma dt / eps^3 = 1.6 > 0.1" in proc.stdout
    scene["numerics"]["dt"] = 5e-6  # S gamma dt / eps^3 = 0.08: within the guide
    assert "warning" not in check(tmp_path, scene).stdout


@pytest.mark.parametrize("steps, every, expected", [(2, 10, 2), (20, 10, 3), (25, 10, 4), (2, 0, 1)])
def test_check_counts_the_outputs_the_run_writes(tmp_path, steps, every, expected):
    """check's count is what the run writes: the initial state, every `every` steps and
    the end (once, also when it falls on a multiple); with every = 0 the end alone."""
    scene = copy.deepcopy(SQUARE)
    scene["numerics"]["end_time"] = steps * 1e-5
    scene["output"] = {"every": every}
    proc = check(tmp_path, scene)
    assert proc.returncode == 0, proc.stderr
    assert re.search(rf"outputs\s+{expected} ", proc.stdout), proc.stdout
    if steps <= 2:
        run_scene(scene, tmp_path)
        import sys
        sys.path.insert(0, str(__import__("pathlib").Path(__file__).parents[2] / "python"))
        from cellphase_results import read_fields
        assert len(list(read_fields(tmp_path / "out"))) == expected


@pytest.mark.parametrize("args", [["--help"], ["-h"], ["help"], ["run", "--help"],
                                  ["check", "scene.yaml", "-h"]])
def test_help_answers_wherever_it_is_asked(args):
    """--help (or -h) anywhere on the command line prints the usage and exits 0, before
    any scene is read."""
    require_exe()
    proc = subprocess.run([EXE, *args], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert "Usage:" in proc.stdout and "docs/scenes.md" in proc.stdout
