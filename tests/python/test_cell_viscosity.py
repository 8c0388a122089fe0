"""Each cell's own viscosity in eta(phi_1, ..., phi_N) = eta_0 (1 - phi_cells)/2
+ sum_i eta_i (1 + phi_i)/2 (thesis 7.12): two tilted ellipses in a shear flow."""
import copy

import pytest

from conftest import run_scene
from test_many_cells import check

SCENE = {
    "domain": {"lower": [-1.5, -0.75], "upper": [1.5, 0.75], "resolution": [24, 12]},
    "cells": [{"name": "left", "shape": "ellipse", "center": [-0.6, 0], "semi_axes": [0.3, 0.2],
               "rotation": 45},
              {"name": "right", "shape": "ellipse", "center": [0.6, 0], "semi_axes": [0.3, 0.2],
               "rotation": 45}],
    "phase_field": {"model": "helfrich_hm1", "mobility": 1e-3, "penalty_area": 100},
    "numbers": {"Be": 10.0},
    "flow": {"equations": "stokes",
             "walls": {"bottom": {"type": "moving", "velocity": [-2, 0]},
                       "top": {"type": "moving", "velocity": [2, 0]}}},
    "numerics": {"epsilon": 0.04, "dt": 5e-3, "end_time": 0.05,
                 "mesh": {"remesh_every": 5, "points_across_interface": 4, "cell_meshes": "own"}},
}


def with_viscosities(left, right):
    s = copy.deepcopy(SCENE)
    for cell, eta in zip(s["cells"], (left, right)):
        if eta is not None:
            cell["viscosity"] = eta
    return s


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    return {name: run_scene(with_viscosities(*etas), tmp_path_factory.mktemp(name))
            for name, etas in [("default", (None, None)), ("ones", (1, 1)), ("viscous", (1, 20))]}


def test_the_cells_viscosity_equal_to_the_fluids_gives_eta_of_phi_cells(runs):
    # eta(phi_1, phi_2) with eta_i = 1 is 1 everywhere, as eta(phi_cells) with equal
    # viscosities: the two forms differ only in how eta is written (P2 nodes against the
    # clipped phase field), so the runs agree to round-off of the solves.
    for key in ("left.center_y", "right.center_y", "left.circularity", "right.circularity"):
        diff = max(abs(a - b) for a, b in zip(runs["default"][key], runs["ones"][key]))
        assert diff < 1e-9, f"{key}: {diff:.1e}"


def test_a_viscous_cell_relaxes_more_slowly(runs):
    c = runs["viscous"]
    # Both start as the same tilted ellipse; the shear and the bending force round them.
    # Measured over 10 steps: circularity +0.0103 (eta = 1) and +0.0039 (eta = 20).
    soft = c["left.circularity"][-1] - c["left.circularity"][0]
    stiff = c["right.circularity"][-1] - c["right.circularity"][0]
    print(f"circularity change: eta 1 {soft:.4f}, eta 20 {stiff:.4f}")
    assert soft > 0 and stiff > 0
    assert stiff < 0.6 * soft
    # Each cell's velocity column int phi~_i v / int phi~_i moves its centre: the mean of
    # the column over the run against the centre's displacement (trapezoidal rule).
    t = c["time"]
    for cell in ("left", "right"):
        v = c[f"{cell}.velocity_y"]
        moved = sum((t[k + 1] - t[k]) * (v[k] + v[k + 1]) / 2 for k in range(1, len(t) - 1))
        moved += (t[1] - t[0]) * v[1]  # the first step's velocity is v^1
        dy = c[f"{cell}.center_y"][-1] - c[f"{cell}.center_y"][0]
        print(f"{cell}: centre moved {dy:.5f}, velocity column gives {moved:.5f}")
        assert abs(moved - dy) < 0.03 * abs(dy)
    # With equal viscosities the two cells mirror each other.
    d = runs["ones"]
    assert abs(d["left.circularity"][-1] - d["right.circularity"][-1]) < 1e-8


@pytest.mark.parametrize("change, message", [
    (lambda s: s["cells"][1].update(viscosity=-1), "cells[1] (\"right\").viscosity"),
    (lambda s: s.pop("flow"), "has no flow section"),
    (lambda s: [c.update(group="both") for c in s["cells"]] + [c.update(viscosity=3) for c in s["cells"]],
     "one phase field; use flow.viscosity.inside"),
    (lambda s: [c.update(group="both") for c in s["cells"]] + [s["cells"][0].update(viscosity=3)],
     "differs from that of"),
])
def test_bad_cell_viscosity_stops_before_the_first_step(tmp_path, change, message):
    scene = with_viscosities(None, 5)
    change(scene)
    proc = check(tmp_path, scene)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "error:" in proc.stderr and message in proc.stderr, proc.stderr
