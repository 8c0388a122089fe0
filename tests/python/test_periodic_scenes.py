"""Periodic directions (domain.periodic, dolfinx_mpc through compat/Periodic) in whole runs:
the flow and the phase field are solved on the constrained spaces, the pressure of a box
closed by walls and periodic sides is pinned and shifted to zero mean.

The scenes carry a Cahn-Hilliard droplet with equal densities and viscosities and zero
surface tension: the flow does not feel it, so the flow is that of the empty channel."""
import sys
from pathlib import Path

import numpy as np

from conftest import run_scene
from test_checkpoint import assert_same_observables, restart_from_shorter_run

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import cellphase_results  # noqa: E402


def droplet_scene(flow, dt, end_time, remesh_every=0, **output):
    return {
        "domain": {"lower": [0, 0], "upper": [1, 1], "resolution": [8, 8], "periodic": ["x"]},
        "cells": [{"shape": "circle", "center": [0.5, 0.5], "radius": 0.15}],
        "phase_field": {"model": "cahn_hilliard", "mobility": 1e-4},
        "numbers": {"Re": 1, "Ca": 1},
        "flow": {"equations": "stokes", "surface_tension": 0, **flow},
        "numerics": {"epsilon": 0.06, "dt": dt, "end_time": end_time,
                     "mesh": {"remesh_every": remesh_every, "points_across_interface": 3}},
        "output": {"every": 0, "progress": False, **output},
    }


# Both walls moving with (1, 0): the Stokes solution is the uniform flow v = (1, 0).
UNIFORM = {"walls": {"bottom": {"type": "moving", "velocity": [1, 0]},
                     "top": {"type": "moving", "velocity": [1, 0]}}}


def test_periodic_channel_has_the_analytic_parabola(tmp_path):
    """Plane Poiseuille flow driven by the body force f between no-slip walls at y = 0, 1:
    -v'' = f, v = f y (1 - y) / 2 (div(2 D(v)) = v'' for v = (v(y), 0), eta = 1). The
    parabola is in the P2 velocity space, so the discrete solution is exact up to the
    round-off of the LU solve: 5e-15 seen, asserted 1e-12 (of the maximum 0.25)."""
    f = 2.0
    scene = droplet_scene({"force": [f, 0]}, dt=0.01, end_time=0.02,
                          every=1, fields=["phi", "v", "p"])
    c = run_scene(scene, tmp_path)
    assert c["cell_velocity_x"][-1] > 0.2  # the droplet is carried along
    checked = 0
    for time, points, _, values in cellphase_results.read_fields(tmp_path / "out"):
        if time == 0:
            continue
        y, v = points[:, 1], values["v"]
        assert np.abs(v[:, 0] - f * y * (1 - y) / 2).max() < 1e-12
        assert np.abs(v[:, 1]).max() < 1e-12
        # The pressure is periodic and the force is balanced by the walls: p = const = 0
        # after the zero-mean shift (pinned dof on the min faces, not a slave).
        assert np.abs(values["p"]).max() < 1e-11
        checked += 1
    assert checked == 2


def test_droplet_advected_once_around_keeps_volume_and_comes_back(tmp_path):
    """v = (1, 0) carries the droplet across x = 1 and back to its start in t = 1; the
    mesh follows it (remeshing every step; the band refines both periodic faces alike
    while it crosses). int phi is kept to round-off (2e-14 seen): no flux through the
    periodic faces, conservative advection, volume-corrected transfer. The position follows
    x = 0.5 + t up to a lag of the time discretisation: 0.0084 at t = 1 with dt = 1/32,
    0.0020 with dt = 1/64, asserted < 0.015 for dt = 1/32."""
    c = run_scene(droplet_scene(UNIFORM, dt=1 / 32, end_time=1.0, remesh_every=1), tmp_path)
    v0 = c["volume"][0]
    assert max(abs(v - v0) for v in c["volume"]) < 1e-12 * v0
    assert max(abs(u - 1) for u in c["cell_velocity_x"][1:]) < 1e-12
    assert c["time"][-1] == 1.0
    # Moving at speed 1 (0.6215 at t = 1/8). The centre is taken on the axis opened away
    # from the droplet and continued across the periodic face: 0.5 + t throughout, also
    # while the droplet straddles x = 1, and 1.5 (one period on) at the end.
    lag = [abs(x - (0.5 + t)) for x, t in zip(c["center_x"], c["time"])]
    assert max(lag) < 0.015, max(lag)
    assert abs(c["center_x"][-1] - 1.5) < 0.015
    assert abs(c["center_y"][-1] - 0.5) < 1e-12


def long_channel_on_own_meshes(center_x, end_time):
    s = droplet_scene(UNIFORM, dt=1 / 32, end_time=end_time, remesh_every=1)
    s["domain"].update(upper=[3, 1], resolution=[24, 8])
    s["cells"][0]["center"] = [center_x, 0.5]
    s["numerics"]["mesh"].update(cell_meshes="own", own_margin=0.36)
    return s


def test_own_mesh_crosses_the_periodic_side_on_a_wrapped_patch(tmp_path):
    """numerics.mesh.cell_meshes: own on a periodic channel three times as long. The droplet
    starting at x = 2.5 crosses x = 3 on its own patch, whose part beyond the side lies a
    period up (a wrapped patch), and ends at x = 3.5 on a plain patch again; the droplet
    starting at x = 1 moves as far without nearing a side. The shift, 12 base cells, maps
    the base mesh onto itself, so the two runs must have the same patches (the same cell
    dofs every step) and the same observables up to round-off (2e-14 seen in
    centre_x - 1.5, asserted 1e-10). On 2 MPI ranks the side's two columns of base cells lie on different
    ranks (stripes): the same dofs and observables."""
    runs = {}
    for name, x0, ranks in (("inside", 1.0, 1), ("across", 2.5, 1), ("across-mpi", 2.5, 2)):
        (tmp_path / name).mkdir()
        runs[name] = run_scene(long_channel_on_own_meshes(x0, 1.0), tmp_path / name, ranks=ranks)
    inside, across = runs["inside"], runs["across"]
    assert across["center_x"][-1] > 3.45  # it went across, a period on
    # The cell's patches alike (the flow's mesh differs: both periodic faces are refined
    # while the droplet is near x = 3).
    cell = {k: [d - f for d, f in zip(c["dofs"], c["flow_dofs"])] for k, c in runs.items()}
    assert cell["inside"] == cell["across"] == cell["across-mpi"]
    assert across["dofs"] == runs["across-mpi"]["dofs"]
    shift = max(abs(a - 1.5 - b) for a, b in zip(across["center_x"], inside["center_x"]))
    print("centre_x: across - 1.5 against inside", shift)
    assert shift < 1e-10
    for key in ("volume", "surface", "center_y", "cell_velocity_x", "phi_min"):
        for other in ("inside", "across-mpi"):
            for a, b in zip(across[key], runs[other][key]):
                assert abs(a - b) <= 1e-10 * max(abs(a), 1e-12), (key, other)
    v0 = across["volume"][0]
    assert max(abs(v - v0) for v in across["volume"]) < 1e-12 * v0


def test_periodic_restart_equals_uninterrupted(tmp_path):
    """Run to step 8 and continued to 14 (remeshing every 3 steps, while the droplet nears
    the periodic face) equals the run in one go bit for bit."""
    def scene(end):
        return droplet_scene(UNIFORM, dt=1 / 16, end_time=end, remesh_every=3,
                             checkpoints={"every": 4, "keep": 2})
    full, continued, stdout = restart_from_shorter_run(scene(14 / 16), scene(8 / 16), tmp_path)
    assert "(step 8," in stdout
    assert_same_observables(full, continued)


def test_periodic_droplet_on_two_ranks_equals_serial(tmp_path):
    """The droplet of the test above carried across the periodic face x = 1 (remeshing
    every step) on 2 MPI ranks: the constraint's slaves and masters then lie on different
    ranks. Same dofs every step; observables equal to serial up to the round-off of the
    parallel sums and solves (4.5e-14 seen, asserted 1e-10)."""
    scene = droplet_scene(UNIFORM, dt=1 / 32, end_time=0.5, remesh_every=1)
    scene["cells"][0]["center"] = [0.6, 0.5]
    (tmp_path / "serial").mkdir()
    (tmp_path / "mpi").mkdir()
    serial = run_scene(scene, tmp_path / "serial")
    mpi = run_scene(scene, tmp_path / "mpi", ranks=2)
    assert serial["dofs"] == mpi["dofs"]
    assert serial["center_x"][-1] > 1.05  # it went across the face
    for key in ("volume", "surface", "center_x", "center_y", "cell_velocity_x"):
        for a, b in zip(serial[key], mpi[key]):
            assert abs(a - b) <= 1e-10 * max(abs(a), 1e-12), key
