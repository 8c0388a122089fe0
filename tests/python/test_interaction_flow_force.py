"""interaction.flow_force: false keeps the interaction's part of each cell's phi# out of the
flow's force (7.12). Summed over the cells that part is the gradient
(1/In) grad sum_{i != j} B(phi_i) w_j, which the pressure absorbs in the continuous model;
discretely it is not, and with the Lennard-Jones-like potential of Fig. 7.7b its remainder
drives a flow of its own. The potential then acts through the mobility term alone,
gamma Lap(w + w_int), the same phase-field step in exact arithmetic. (That it still keeps
cells apart in a flow: test_many_cells, the two cells in shear.)"""
import pytest
import yaml

from conftest import run_scene
from test_interaction_pairs import COMPARED, LJ, largest_difference, with_interaction
from test_many_cells import TWO, check


def runs_of(base, variants, tmp_path):
    out = {}
    for name, interaction in variants.items():
        (tmp_path / name).mkdir()
        out[name] = run_scene(with_interaction(base, interaction), tmp_path / name)
    return out


def test_without_flow_the_phase_field_step_is_the_same(tmp_path):
    # w + w_int in the mobility term instead of w_int inside w: the same linear system up
    # to the order of round-off (the L2 projection is the w row's own mass matrix).
    r = runs_of(TWO, {"in_w": {"In": 1.0}, "in_mobility": {"In": 1.0, "flow_force": False}},
                tmp_path)
    diff = largest_difference(r["in_mobility"], r["in_w"], COMPARED)
    print("flow_force false against true, no flow: "
          + ", ".join(f"{k} {v:.1e}" for k, v in diff.items()))
    assert abs(r["in_w"]["interaction_energy"][0]) > 0.01
    # measured 1.1e-13 after 12 steps; 1e-10 as for the pairs of test_interaction_pairs
    assert max(diff.values()) < 1e-10, diff


def two_rbcs(steps):
    """Two RBCs of the bifurcation demo (eps 0.04, mobility 1e-7, Be 2.5, viscosity ratio
    10, force 1/Fr) side by side in a periodic channel, 3.3 eps apart, with the
    Lennard-Jones-like potential of Fig. 7.7b at In = 0.01 (derivative_reach 3)."""
    return {
        "domain": {"lower": [-0.7, -0.3], "upper": [0.7, 0.3], "resolution": [14, 6],
                   "periodic": ["x"]},
        "cells": [{"name": "a", "shape": "cassini", "center": [-0.3, 0.02], "a": 0.15, "b": 0.18},
                  {"name": "b", "shape": "cassini", "center": [0.3, -0.02], "a": 0.15, "b": 0.18}],
        "phase_field": {"model": "helfrich_hm1", "mobility": 1e-7, "penalty_area": 100},
        "numbers": {"Re": 1.125e-4, "Be": 2.5},
        "flow": {"equations": "navier_stokes", "viscosity": {"inside": 10, "outside": 1},
                 "force": [46.875, 0], "coupling_stabilisation": 1e-6},
        "numerics": {"epsilon": 0.04, "dt": 1e-3, "end_time": steps * 1e-3,
                     "mesh": {"remesh_every": 5, "points_across_interface": 5}},
    }


def test_the_adhesive_potential_drives_no_flow_of_its_own(tmp_path):
    lj = {"In": 0.01, **LJ, "derivative_reach": 3}
    r = runs_of(two_rbcs(30), {"free": None, "in_flow": lj,
                               "out_of_flow": {**lj, "flow_force": False}}, tmp_path)
    v = {k: c["cell_velocity_x"] for k, c in r.items()}
    for k, c in r.items():
        print(f"{k}: v_cell " + " ".join(f"{x:.3f}" for x in v[k][::5])
              + f"; overlap {c['overlap_max'][0]:.3f} -> {c['overlap_max'][-1]:.3f}")
    free, out, into = v["free"], v["out_of_flow"], v["in_flow"]
    deviation = max(abs(a - b) / abs(b) for a, b in zip(out[1:], free[1:]))
    spurious = max(abs(a - b) / abs(b) for a, b in zip(into[1:], free[1:]))
    print(f"largest relative difference of v_cell from the free cells: {deviation:.1e} "
          f"(flow_force false), {spurious:.1e} (true)")
    # With the potential in the force the discrete remainder drives the cells at up to
    # seven times the free speed (measured 9.3 against 1.34) and pulls them together
    # (overlap 0.086 -> 0.17); without it v_cell follows the free cells' to 2.9e-3
    # (measured; the potential acts through the mobility 1e-7 and the shapes only, bound
    # 1e-2), and the overlap stays near its start (0.086 -> 0.082, free 0.081).
    assert spurious > 1.0
    assert deviation < 1e-2
    assert r["out_of_flow"]["overlap_max"][-1] < 1.1 * r["out_of_flow"]["overlap_max"][0]
    for cell in ("a", "b"):
        vol = r["out_of_flow"][f"{cell}.volume"]
        assert max(abs(x - vol[0]) for x in vol) < 1e-10 * vol[0]


def test_refresh_with_the_interaction_out_of_the_flow_is_refused(tmp_path):
    proc = check(tmp_path, with_interaction(TWO, {"In": 1.0, "refresh": True, "flow_force": False}))
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "interaction.refresh" in proc.stderr and "flow_force: false" in proc.stderr, proc.stderr


def test_check_says_where_the_interaction_acts(tmp_path):
    proc = check(tmp_path, with_interaction(TWO, {"In": 1.0, "flow_force": False}))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "not in the flow's force (flow_force: false" in proc.stdout, proc.stdout
