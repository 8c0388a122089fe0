"""Scenes on mesh files (domain.mesh): the bifurcated vessel of meshes/bifurcation.geo
(thesis Fig. 7.4) runs two coupled Stokes steps with a remesh before each, with a
parabolic inflow given by a formula and open outlets; `cellphase check` lists the tags."""
import subprocess

import yaml

from conftest import EXE, require_exe, run_scene

SCENE = {
    "domain": {"mesh": "meshes/bifurcation.xdmf"},  # built from meshes/bifurcation.geo
    "cells": [{"name": "c", "shape": "circle", "center": [1.5, 0], "radius": 0.3}],
    "phase_field": {"model": "helfrich_penalty", "penalty_volume": 1000, "penalty_area": 100},
    "numbers": {"Re": 0, "Ca": 1, "Be": 2.5},
    "numerics": {"epsilon": 0.04, "dt": 1e-3, "end_time": 2e-3,
                 "mesh": {"remesh_every": 1}},
    "flow": {"equations": "stokes",
             "walls": {"inflow": {"type": "prescribed", "velocity": ["1.5*(1-4*y^2)", 0]},
                       "outflow_upper": "open", "outflow_lower": "open"}},
}


def test_bifurcation_runs_two_steps_with_remeshing(tmp_path):
    obs = run_scene(SCENE, tmp_path)
    assert obs["step"] == [0, 1, 2]
    v0 = obs["volume"][0]
    assert all(abs(v - v0) / v0 < 1e-2 for v in obs["volume"])
    # The inflow (mean velocity 1) carries the cell downstream: about 1e-3 per step.
    dx = obs["center_x"][2] - obs["center_x"][0]
    assert 1e-3 < dx < 4e-3, dx


def test_check_lists_the_tags(tmp_path):
    require_exe()
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(SCENE))
    out = subprocess.run([EXE, "check", str(path)], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert "boundary tags         inflow (length 1), outflow_lower (length 0.7)" in out.stdout
    assert "inflow prescribed (1.5*(1-4*y^2), 0)" in out.stdout
