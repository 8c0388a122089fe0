"""Each cell on its own mesh (numerics.mesh.cell_meshes: own, section 7.2): its phase field on
the patch of the base mesh around it, refined around it only; the flow on the shared mesh.
Compared with the shared mesh, restarted, run on two ranks, and stopped when a cell leaves
its patch."""
import copy
import csv
import pathlib
import subprocess

import pytest
import yaml

from conftest import EXE, mpirun_prefix, require_exe, run_scene
from test_many_cells import TWO, check

OWN = {"cell_meshes": "own"}
REPO = pathlib.Path(__file__).resolve().parents[2]


def with_mesh(scene, **mesh):
    s = copy.deepcopy(scene)
    s["numerics"]["mesh"].update(mesh)
    return s


@pytest.fixture(scope="module")
def pushed(tmp_path_factory):
    """The two overlapping circles of test_many_cells pushed apart by the potential."""
    scene = copy.deepcopy(TWO)
    scene["interaction"] = {"In": 1.0}
    return {name: run_scene(with_mesh(scene, cell_meshes=name), tmp_path_factory.mktemp(name))
            for name in ("shared", "own")}


def test_own_meshes_give_the_shared_mesh_result_with_fewer_dofs(pushed):
    own, shared = pushed["own"], pushed["shared"]
    print(f"dofs: own {own['dofs'][0]:.0f}, shared {shared['dofs'][0]:.0f}")
    # Each patch is refined around its own cell only.
    assert own["dofs"][0] < 0.7 * shared["dofs"][0]
    # The meshes differ where the other cell's band lies, so the results agree to the
    # discretisation error, not to round-off. Measured after 12 steps: centre 1.5e-4 (the
    # displacement itself is 0.027), overlap 1e-4, energy 5e-4 relative.
    for key, tol in [("left.center_x", 1e-3), ("right.center_x", 1e-3), ("overlap_max", 1e-3)]:
        diff = max(abs(a - b) for a, b in zip(own[key], shared[key]))
        print(f"{key}: own - shared {diff:.1e}")
        assert diff < tol
    assert abs(own["total_energy"][-1] / shared["total_energy"][-1] - 1) < 2e-3
    assert own["left.center_x"][-1] < -0.35  # pushed from -0.33 as on the shared mesh


def test_each_cell_keeps_its_volume_across_new_patches_and_the_energy_decays(pushed):
    c = pushed["own"]
    for cell in ("left", "right"):
        v = c[f"{cell}.volume"]
        drift = max(abs(x - v[0]) for x in v) / v[0]
        print(f"{cell}: volume drift {drift:.1e} over two remeshes (new patches)")
        # int (1 + phi) is kept when a patch changes: H^-1 flow and transfer, to round-off.
        assert drift < 1e-10
    e = c["total_energy"][4:]  # the explicit interaction source: see test_many_cells
    assert not [b - a for a, b in zip(e, e[1:]) if b > a + 1e-9 * abs(e[0])]


# One ellipse relaxing in a shear flow between walls moving at +-4.
SHEAR = {
    "domain": {"lower": [-1.5, -0.75], "upper": [1.5, 0.75], "resolution": [24, 12]},
    "cells": [{"shape": "ellipse", "center": [-0.28, 0.13], "semi_axes": [0.3, 0.2]}],
    "phase_field": {"model": "helfrich_hm1", "mobility": 1e-3, "penalty_area": 100},
    "numbers": {"Be": 10.0},
    "flow": {"equations": "stokes",
             "walls": {"bottom": {"type": "moving", "velocity": [-4, 0]},
                       "top": {"type": "moving", "velocity": [4, 0]}}},
    "numerics": {"epsilon": 0.04, "dt": 5e-3, "end_time": 0.05,
                 "mesh": {"remesh_every": 5, "points_across_interface": 4}},
}


def test_own_mesh_advection_has_no_bulk_source(tmp_path):
    """On a cell's own mesh phi + 1 is advected (forms/cellphase_ufl.py): it is zero beyond the
    patch's edge, and outside the cell the weakly divergence-free Taylor-Hood velocity adds no
    source phi div v_h. The shared mesh's -phi v.grad(psi) has that source in the coarse bulk,
    where refining around the interface does not reduce it: its Helfrich energy approaches the
    own mesh's only as the base mesh is refined."""
    runs = {}
    for name, mesh, res in [("own", "own", [24, 12]), ("shared", "shared", [24, 12]),
                            ("shared, base x4", "shared", [96, 48])]:
        scene = with_mesh(SHEAR, cell_meshes=mesh)
        scene["domain"]["resolution"] = res
        (tmp_path / name.replace(" ", "").replace(",", "")).mkdir()
        runs[name] = run_scene(scene, tmp_path / name.replace(" ", "").replace(",", ""))
    e = {k: r["helfrich_energy"][-1] for k, r in runs.items()}
    print("Helfrich energy at t = 0.05: " + ", ".join(f"{k} {v:.4f}" for k, v in e.items()))
    # Measured: own 1.375, shared 1.602, shared on the 4x finer base 1.389.
    assert abs(e["own"] - e["shared, base x4"]) < 0.25 * abs(e["shared"] - e["shared, base x4"])
    # The cell relaxes towards a circle: its bending energy falls on its own mesh.
    assert runs["own"]["circularity"][-1] > runs["own"]["circularity"][0]
    assert e["own"] < runs["own"]["helfrich_energy"][1]
    v = runs["own"]["volume"]
    assert max(abs(x - v[0]) for x in v) < 1e-10 * v[0]
    # The flow carries phi + 1 out across the patch's edge (the upwind outflow term) and the
    # step puts it back into the interface: what was put back, 6e-6 of the volume (measured),
    # is far above the volume's drift, so the volume is kept by the put-back, not by chance.
    returned = runs["own"]["edge_outflow"]
    print(f"put back after leaving the patch: {returned[-1]:.1e} of the volume")
    assert abs(returned[-1]) > 1e-7 and returned[0] == 0


def test_the_volume_multiplier_alone_keeps_an_l2_cell_volume_on_its_own_mesh(tmp_path):
    """helfrich_lagrange holds the volume at t^{n+1} by its multiplier, whatever left across
    the patch's edge; the put-back of the H^-1 flows would add it a second time (measured:
    a drift of 3e-5 with it, 1e-13 without)."""
    scene = with_mesh(SHEAR, cell_meshes="own")
    scene["phase_field"] = {"model": "helfrich_lagrange"}
    run = run_scene(scene, tmp_path)
    v = run["volume"]
    print(f"volume drift {max(abs(x - v[0]) for x in v) / v[0]:.1e}, "
          f"carried out {run['edge_outflow'][-1]:.1e}")
    assert abs(run["edge_outflow"][-1]) > 1e-5
    assert max(abs(x - v[0]) for x in v) < 1e-10 * v[0]


def cut_and_restart(scene, workdir, ranks):
    """Run `scene` to t = 0.02, restart it from its checkpoint to the end on the same number
    of ranks, and return the observables of the whole sequence."""
    workdir.mkdir()
    cut = copy.deepcopy(scene)
    cut["numerics"]["end_time"] = 0.02
    run_scene(cut, workdir, ranks=ranks)
    again = copy.deepcopy(scene)
    again["output"] = {"every": 0, "progress": False, "directory": str(workdir / "out"),
                       "checkpoints": {"every": 4, "keep": 3}}
    path = workdir / "continue.yaml"
    path.write_text(yaml.safe_dump(again))
    require_exe()
    proc = subprocess.run(mpirun_prefix(ranks) + [EXE, "run", str(path), "--restart",
                                                  str(workdir / "out")],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with open(workdir / "out" / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def test_own_meshes_in_a_flow_restart_bit_for_bit_on_one_and_two_ranks(tmp_path):
    scene = with_mesh(SHEAR, cell_meshes="own")
    scene["cells"] = [
        {"name": "upper", "shape": "circle", "center": [-0.28, 0.13], "radius": 0.25},
        {"name": "lower", "shape": "circle", "center": [0.28, -0.13], "radius": 0.25}]
    scene["interaction"] = {"In": 0.1}
    scene["output"] = {"checkpoints": {"every": 4, "keep": 3}}
    whole = {}
    for ranks in (1, 2):
        (tmp_path / f"whole{ranks}").mkdir()
        whole[ranks] = run_scene(scene, tmp_path / f"whole{ranks}", ranks=ranks)  # 10 steps
        restarted = cut_and_restart(scene, tmp_path / f"cut{ranks}", ranks)
        assert len(restarted["step"]) == len(whole[ranks]["step"]) == 11
        if ranks == 1:
            for k in (k for k in whole[1] if not k.startswith("wall_")):
                assert restarted[k] == whole[1][k], f"{k} differs after the restart"
        else:  # two runs on 2 ranks differ in round-off already (the order of MPI sums)
            assert_close(restarted, whole[2], "restarted on 2 ranks")
        for cell in ("upper", "lower"):
            v = whole[ranks][f"{cell}.volume"]
            assert max(abs(x - v[0]) for x in v) < 1e-10 * v[0]
    # On two ranks each patch is cut on the ranks of its base cells and shares its nodes
    # across the rank boundary (compat/Patch.cpp; both patches span both ranks here), so the
    # run is the one-rank run up to the order of the floating-point sums (assembly and MUMPS
    # split across ranks). Measured: 7e-12 (a multiplier), 1e-13 elsewhere.
    assert_close(whole[2], whole[1], "2 ranks against 1")


def assert_close(a, b, what, rel=1e-9):
    """Observables equal to round-off, relative to max(1, |value|). The inclination of two
    near-round cells is the axis of a nearly isotropic moment tensor: round-off moves it by
    up to 1e-7 degrees (measured), so it gets 1e-6 degrees."""
    for k in (k for k in b if not k.startswith("wall_")):
        scale = max(1.0, max(abs(x) for x in b[k]))
        diff = max(abs(x - y) for x, y in zip(a[k], b[k]))
        bound = 1e-6 if k == "inclination_deg" else rel * scale
        assert diff < bound, f"{k}: {what} differs by {diff:.1e}"


@pytest.mark.parametrize("partition", ["stripes", "graph"])
def test_patches_that_meet_on_a_rank_boundary_give_the_one_rank_result(tmp_path, partition):
    """The two cells of demos/cell-collision, 12 steps, on two ranks split in stripes (the
    default with own meshes, mesh/BaseMesh: every patch crosses several rank boundaries)
    and by DOLFINx's graph partitioner (random from run to run; it often cuts the patches
    where they meet). A node at one patch's edge then lies on a rank that holds none of the
    other patch's cells beside it. Measured with the graph partition before
    compat/RemotePoints and the owners' share of a copy's writes: 1e-8 apart from step 7 in
    two of three runs; with them 1e-11 in every run, and 5e-10 (lambda_area) in stripes.
    The same scene also keeps 1e-11 on the shared mesh up to contact (step 31), where both
    go to 1e-6 as the parallel direct solve pivots in another order."""
    scene = yaml.safe_load((REPO / "demos" / "cell-collision" / "scene.yaml").read_text())
    scene["numerics"]["end_time"] = 12 * scene["numerics"]["dt"]
    scene["numerics"]["mesh"]["partition"] = partition
    scene["output"] = {}
    runs = {}
    for ranks in (1, 2):
        (tmp_path / str(ranks)).mkdir()
        runs[ranks] = run_scene(scene, tmp_path / str(ranks), ranks=ranks)
    assert_close(runs[2], runs[1], "2 ranks against 1")


def test_a_cell_that_leaves_its_patch_stops_with_a_message(tmp_path):
    # Walls at +-40 carry the cell about 0.35 in 10 steps; the patch was cut at the start only.
    scene = with_mesh(SHEAR, cell_meshes="own", remesh_every=0, own_margin=0.25)
    scene["flow"]["walls"]["bottom"]["velocity"] = [-40, 0]
    scene["flow"]["walls"]["top"]["velocity"] = [40, 0]
    require_exe()
    scene["output"] = {"every": 0, "progress": False, "directory": str(tmp_path / "out")}
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene))
    proc = subprocess.run([EXE, "run", str(path)], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 3, proc.stdout + proc.stderr
    assert "edge of its own mesh" in proc.stderr and "own_margin" in proc.stderr, proc.stderr
    assert list((tmp_path / "out" / "checkpoints").glob("*.cpk"))  # the last good state


@pytest.mark.parametrize("change, message", [
    (lambda s: s["numerics"]["mesh"].update(own_margin=0.05), "own_margin"),
    (lambda s: s["phase_field"].update(model="allen_cahn_volume"), "allen_cahn_volume"),
    (lambda s: s["numerics"]["mesh"].update(cell_meshes="private"), "cell_meshes"),
    (lambda s: s["numerics"]["mesh"].update(partition="slices"), "partition"),
    (lambda s: s["numerics"]["mesh"].update(stripe_width=0.01), "stripe_width"),
    (lambda s: s["numerics"]["mesh"].update(partition="graph", stripe_width=0.5), "stripe_width"),
])
def test_bad_own_mesh_input_stops_before_the_first_step(tmp_path, change, message):
    scene = with_mesh(TWO, cell_meshes="own")
    change(scene)
    proc = check(tmp_path, scene)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "error:" in proc.stderr and message in proc.stderr, proc.stderr


def test_two_cells_across_a_periodic_side_interact_as_away_from_it(tmp_path):
    """The pushed pair in a channel periodic in x, once in the middle and once moved by two
    base cells towards x = -1: the left cell's patch then wraps across the periodic side
    (its part beyond x = -1 lies a period up, at x > 1), and the pair's band boxes meet only
    at their nearest images. Without that the pair would not interact at all. The meshes
    are refined alike only up to the refinement's tie-breaks (the symmetric pair's two
    cells differ by 0.6 % in their initial Helfrich energy), so the runs agree to the
    discretisation error, not to round-off. Seen: interaction energy 2.2e-2, overlap
    6.4e-3 (relative), centres 2.2e-4 apart; each cell keeps its volume to 1e-10 in both."""
    scene = copy.deepcopy(TWO)
    scene["domain"]["periodic"] = ["x"]
    scene["interaction"] = {"In": 1.0}
    scene["numerics"]["mesh"].update(cell_meshes="own", own_margin=0.24)
    runs = {}
    for name, shift in (("middle", 0.0), ("across", -0.2)):
        s = copy.deepcopy(scene)
        for cell in s["cells"]:
            cell["center"][0] += shift
        (tmp_path / name).mkdir()
        runs[name] = run_scene(s, tmp_path / name)
    middle, across = runs["middle"], runs["across"]
    assert middle["overlap_max"][-1] > 0.1  # the cells interact
    for key, rel in (("interaction_energy", 5e-2), ("overlap_max", 2e-2)):
        worst = max(abs(a - b) / abs(a) for a, b in zip(middle[key], across[key]))
        print(f"{key}: across against middle {worst:.1e} (relative)")
        assert worst < rel, key
    for cell in ("left", "right"):
        gap = max(abs(b - a + 0.2) for a, b in zip(middle[f"{cell}.center_x"], across[f"{cell}.center_x"]))
        print(f"{cell}.center_x: across + 0.2 against middle {gap:.1e}")
        assert gap < 1e-3
        assert middle[f"{cell}.center_x"][-1] * (1 if cell == "right" else -1) > 0.35  # pushed apart
        for run in runs.values():
            v = run[f"{cell}.volume"]
            assert max(abs(x - v[0]) for x in v) < 1e-10 * v[0]
