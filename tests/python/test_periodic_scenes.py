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


def test_own_mesh_crosses_the_periodic_side_on_the_whole_domain(tmp_path):
    """numerics.mesh.cell_meshes: own on a periodic channel three times as long: the droplet
    starts on a patch (cut edges, phi + 1 advected), gets the whole domain once its patch
    would come within two base cells of x = 3 (a patch is not wrapped around a periodic
    side), crosses x = 3 there as on the shared mesh and returns to a patch. The volume is
    kept to round-off throughout and the droplet moves as on the shared mesh."""
    def scene(cell_meshes):
        s = droplet_scene(UNIFORM, dt=1 / 32, end_time=3.0, remesh_every=1)
        s["domain"].update(upper=[3, 1], resolution=[24, 8])
        s["cells"][0]["center"] = [1.5, 0.5]
        s["numerics"]["mesh"].update(cell_meshes=cell_meshes, own_margin=0.36)
        return s
    (tmp_path / "shared").mkdir()
    (tmp_path / "own").mkdir()
    shared = run_scene(scene("shared"), tmp_path / "shared")
    own = run_scene(scene("own"), tmp_path / "own")
    # Round-off of 96 remeshes, each moving phi between the patch, the whole domain and
    # the shared copy with the volume restored by sums over the nodes: 1.5e-12 seen.
    v0 = own["volume"][0]
    assert max(abs(v - v0) for v in own["volume"]) < 1e-11 * v0
    # A patch at the start and the end (fewer cell dofs than the shared mesh's), the whole
    # domain while crossing (the shared mesh's dofs: the same mesh).
    cell = {k: [d - f for d, f in zip(c["dofs"], c["flow_dofs"])]
            for k, c in (("shared", shared), ("own", own))}
    middle = len(cell["own"]) // 2  # t = 1.5: the droplet on x = 3
    assert cell["own"][0] < 0.8 * cell["shared"][0]
    assert cell["own"][middle] == cell["shared"][middle]
    assert cell["own"][-1] < 0.9 * cell["shared"][-1]
    # Seen: centres 1.1e-4 apart up to t = 2.6 (patch, then the whole domain); back on a
    # patch the Cahn-Hilliard droplet's shifted bulk (eps / R = 0.4) leaves through the
    # patch's edges and is put back into its interface (edge_outflow 4.8e-3 of its volume
    # by t = 3), which moves the centre by 4.8e-3.
    crossing = [abs(a - b) for a, b, t in zip(shared["center_x"], own["center_x"], own["time"])
                if t <= 2.6]
    print("centre_x: own against shared up to t = 2.6", max(crossing), "; at the end",
          own["center_x"][-1], shared["center_x"][-1])
    assert max(crossing) < 3e-4, max(crossing)
    assert abs(own["center_x"][-1] - shared["center_x"][-1]) < 1e-2
    assert abs(own["center_x"][-1] - 4.5) < 0.015  # one period on


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
