"""3D: the same modules on tetrahedra. A sphere under the H^-1 Helfrich flow with the area
penalty (3.33)-(3.35) keeps its volume to round-off and does not gain energy."""
from conftest import run_scene


def test_sphere_keeps_volume_under_hm1_flow(tmp_path):
    scene = {
        "domain": {"lower": [-1.2, -1.2, -1.2], "upper": [1.2, 1.2, 1.2], "resolution": [8, 8, 8]},
        "boundary": {"phi": "neumann"},
        "cells": [{"shape": "ellipse", "center": [0, 0, 0], "semi_axes": [0.5, 0.4, 0.4]}],
        "phase_field": {"model": "helfrich_hm1", "penalty_area": 100},
        "numerics": {"epsilon": 0.2, "dt": 1e-3, "end_time": 0.003,
                     "mesh": {"remesh_every": 0, "points_across_interface": 2.5}},
    }
    obs = run_scene(scene, tmp_path)
    volume, energy = obs["volume"], obs["total_energy"]
    assert max(abs(v - volume[0]) for v in volume) / volume[0] < 1e-10
    assert all(b <= a + 1e-12 * abs(energy[0]) for a, b in zip(energy, energy[1:]))
    assert obs["center_z"][0] == 0 or abs(obs["center_z"][0]) < 1e-10
