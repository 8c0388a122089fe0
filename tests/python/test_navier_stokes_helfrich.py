"""Navier-Stokes-Helfrich with the H^-1 flow and area penalty, (3.59)-(3.64): the membrane
force w grad phi (w = dE/dphi, (3.62)) drives the fluid, phi is advected.

Energy law (3.51): E_kin + E_H + p2/(2 Be) (E_CH - A0)^2 never increases. As for the
Cahn-Hilliard coupling the split scheme is not exactly dissipative, but here every step
lowers the energy by orders of magnitude more than round-off, hence the tolerance 1e-9 E0."""
import pytest

from conftest import run_scene

SCHEMES = ["euler", "bdf2"]  # numerics.time_scheme: the energy law holds for both


@pytest.mark.parametrize("scheme", SCHEMES)
def test_relaxing_vesicle_in_fluid_dissipates_energy_and_keeps_volume(tmp_path, scheme):
    scene = {
        "domain": {"lower": [-1, -1], "upper": [1, 1], "resolution": [8, 8]},
        "cells": [{"shape": "ellipse", "center": [0, 0], "semi_axes": [0.6, 0.3]}],
        "phase_field": {"model": "helfrich_hm1", "mobility": 1e-2, "penalty_area": 100},
        "numbers": {"Re": 1, "Be": 1},
        "flow": {},
        "numerics": {"epsilon": 0.08, "dt": 1e-3, "end_time": 0.02, "time_scheme": scheme,
                     "mesh": {"remesh_every": 0, "points_across_interface": 3}},
    }
    c = run_scene(scene, tmp_path)
    E, kin = c["total_energy_kinetic"], c["kinetic_energy"]
    # total = kinetic + the model's energy (Helfrich + area penalty, column total_energy)
    assert all(abs(e - (k + t)) <= 1e-12 * abs(e) for e, k, t in zip(E, kin, c["total_energy"]))
    steps = [b - a for a, b in zip(E, E[1:])]
    assert max(steps) <= 1e-9 * E[0], max(steps)
    assert max(kin) > 1e-4 * E[0]  # the membrane force moves the fluid
    # H^-1 flow + conservative advection: the volume is kept to round-off
    v0 = c["volume"][0]
    assert max(abs(v - v0) for v in c["volume"]) < 1e-10 * v0
    # symmetric ellipse: the centre stays and the long axis stays along x
    assert max(abs(x) for x in c["center_x"] + c["center_y"]) < 1e-8
    assert max(abs(a) for a in c["inclination_deg"]) < 1e-6


@pytest.mark.parametrize("scheme", SCHEMES)
def test_l2_flow_with_multipliers_dissipates_and_keeps_volume_and_area(tmp_path, scheme):
    """L2 flow with volume and area multipliers, (3.81)-(3.85): the force is
    (dE/dphi) grad phi with dE/dphi of (3.84) projected onto P2 after each step."""
    scene = {
        "domain": {"lower": [-1, -1], "upper": [1, 1], "resolution": [8, 8]},
        "cells": [{"shape": "ellipse", "center": [0, 0], "semi_axes": [0.6, 0.3]}],
        "phase_field": {"model": "helfrich_lagrange", "mobility": 1e-2},
        "numbers": {"Re": 1, "Be": 1},
        "flow": {},
        "numerics": {"epsilon": 0.08, "dt": 1e-3, "end_time": 0.02, "time_scheme": scheme,
                     "mesh": {"remesh_every": 0, "points_across_interface": 3}},
    }
    c = run_scene(scene, tmp_path)
    E, kin = c["total_energy_kinetic"], c["kinetic_energy"]
    steps = [b - a for a, b in zip(E, E[1:])]
    assert max(steps) <= 1e-9 * E[0], max(steps)
    assert max(kin) > 1e-3 * E[0]
    v0, a0 = c["volume"][0], c["surface"][0]
    assert max(abs(v - v0) for v in c["volume"]) < 1e-10 * v0   # multiplier at t^{n+1}
    # the area constraint is linearised about phi^n: second order per step, 2.5e-4 seen
    assert max(abs(a - a0) for a in c["surface"]) < 1e-3 * a0
