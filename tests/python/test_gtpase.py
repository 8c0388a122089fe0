"""The GTPase signalling network on the diffuse cell (thesis 2.6, chapter 5; issue 20):
reaction-diffusion alone on a frozen circle, the motile cell pushed by -(1/Fa) c1 grad phi,
restart with random initial data, and the scene's refusals."""
import copy
import math
import re
import subprocess
import sys
from pathlib import Path

import matplotlib
import matplotlib.image
import pytest
import yaml

from conftest import EXE, one_rank_against_two, require_exe, run_scene
from test_checkpoint import assert_same_observables, restart_from_shorter_run

# Table 5.1 (Be = 6.6, Ca = 0.264 for b_N = 1e-17 J, sigma = 5e-6 N/m; gamma/Be = 0.01) and
# the half-loaded start of section 5.4.1.
HALF_LOADED = {
    "c1": {"initial": {"value": 0.1758, "where": "x > 0"}},
    "c2": {"initial": {"value": 0.2186, "where": "x > 0"}},
    "C": {"initial": 9.25},
}


def cell_scene(epsilon=0.1, dt=5e-3, end_time=0.5, frozen=True, flow=False, resolution=8):
    scene = {
        "domain": {"lower": [-2, -2], "upper": [2, 2], "resolution": [resolution, resolution]},
        "cells": [{"name": "cell", "shape": "circle", "center": [0, 0], "radius": 1}],
        "phase_field": {"model": "helfrich_lagrange", "surface_tension": True, "mobility": 0.066},
        "numbers": {"Be": 6.6, "Ca": 0.264},
        "reaction_diffusion": {"model": "gtpase", "species": copy.deepcopy(HALF_LOADED)},
        "numerics": {"epsilon": epsilon, "dt": dt, "end_time": end_time,
                     "mesh": {"remesh_every": 0 if frozen else 10, "points_across_interface": 4}},
    }
    if frozen:
        scene["reaction_diffusion"]["frozen_until"] = 1e3
    if flow:
        # Symmetric about the cell: the volume multiplier of the L2 flow (5.15) acts on the
        # whole domain and shifts phi slightly in the bulk, which moves x_cm (5.19) in a box
        # that is not symmetric about the cell (4.8e-4 in 10 steps in [-3, 5] x [-3, 3],
        # while int phi~ v / int phi~ stays ~1e-6).
        scene["domain"].update(lower=[-4, -3], upper=[4, 3], resolution=[16, 12])
        scene["numbers"].update(Re=1e-3, Fa=0.05)
        scene["flow"] = {"equations": "navier_stokes"}
    return scene


@pytest.fixture(scope="module")
def frozen(tmp_path_factory):
    return run_scene(cell_scene(), tmp_path_factory.mktemp("frozen"))


def test_reaction_diffusion_keeps_the_total_gtpase_mass_to_round_off(frozen):
    m = frozen["rd_mass"]
    drift = max(abs(x - m[0]) for x in m) / m[0]
    print(f"total GTPase amount {m[0]:.12f}, largest relative change {drift:.1e} in "
          f"{len(m) - 1} steps")
    # Every term but d_t vanishes for the test function 1 (forms/gtpase.py): what is left
    # is the round-off of the assembly and of the LU solve, ~1e-16 per step.
    assert drift < 1e-12
    # The membrane takes GTPase from the cytoplasm (q > 0 where the membrane is loaded).
    assert frozen["rd_mass_membrane"][-1] > 1.5 * frozen["rd_mass_membrane"][0]
    # The unregularised amount differs from the conserved one by at most
    # rho int (C + c1 + c2) <= rho |Omega| (max C + 1) (c1 + c2 <= 1: the membrane saturates,
    # (5.6)); C = 9.25 everywhere at the start and obeys a maximum principle.
    gap = max(abs(a - b) for a, b in zip(frozen["rd_mass"], frozen["rd_mass_cell"]))
    print(f"conserved amount against the cell's amount: {gap:.2e} (bound {1e-6 * 16 * 10.25:.2e})")
    assert gap < 1e-6 * 16 * 10.25


def test_the_pattern_becomes_polar_with_the_front_on_the_loaded_side(frozen):
    c_max, c_min = frozen["rd_c1_max"][-1], frozen["rd_c1_min"][-1]
    at_max, at_min = frozen["rd_c1_max_angle_deg"][-1], frozen["rd_c1_min_angle_deg"][-1]
    print(f"t = {frozen['time'][-1]}: c1 max {c_max:.4f} at {at_max:.1f} deg, "
          f"min {c_min:.2e} at {at_min:.1f} deg")
    # One maximum, on the loaded (right) side, and the minimum opposite (the rear).
    assert abs(at_max) < 15
    assert abs(at_min) > 165
    assert c_max > 0.3 and c_min < 0.1 * c_max


@pytest.fixture(scope="module")
def motile(tmp_path_factory):
    scene = cell_scene(dt=1e-3, end_time=0.03, frozen=False, flow=True)
    still = copy.deepcopy(scene)
    del still["numbers"]["Fa"]  # no protrusion force: Fa -> infinity
    return {"motile": run_scene(scene, tmp_path_factory.mktemp("motile")),
            "still": run_scene(still, tmp_path_factory.mktemp("still"))}


def test_the_protrusion_force_moves_the_cell_in_plus_x_and_keeps_volume_and_mass(motile):
    c = motile["motile"]
    x = c["center_x"]
    print(f"x_cm: {x[0]:.2e} -> {x[-1]:.4f} in {len(x) - 1} steps, v_cm {c['cell_velocity_x'][-1]:.3f}")
    assert all(b > a for a, b in zip(x[1:], x[2:])), "the cell does not move steadily in +x"
    assert x[-1] > 0.01
    volume = max(abs(v - c["volume"][0]) for v in c["volume"]) / c["volume"][0]
    mass = max(abs(m - c["rd_mass"][0]) for m in c["rd_mass"]) / c["rd_mass"][0]
    print(f"relative drift: volume {volume:.1e}, GTPase amount {mass:.1e} (remeshes at steps "
          "10, 20, 30)")
    # The volume multiplier holds V to the solver's round-off; the species are scaled back
    # to their amounts after each remesh, so the amount is kept to round-off too.
    assert volume < 1e-10
    assert mass < 1e-12


def test_without_protrusion_the_cell_does_not_move(motile):
    moved = motile["motile"]["center_x"][-1]
    drift = max(abs(x) for x in motile["still"]["center_x"])
    speed = max(abs(v) for v in motile["still"]["cell_velocity_x"])
    print(f"x_cm drift without protrusion {drift:.1e} (with it {moved:.2e}), "
          f"largest |v_cm| {speed:.1e}")
    # The circle's own forces are radial, and the mesh is mirror-symmetric about x = 0 here:
    # what is left is round-off.
    assert drift < 1e-10
    assert speed < 1e-8


def test_restart_continues_random_initial_data_bit_for_bit(tmp_path):
    scene = cell_scene(dt=1e-3, end_time=0.012, frozen=False, flow=True)
    scene["numerics"]["mesh"]["remesh_every"] = 4
    # Fig. 5.7: random c1, c2 about the homogeneous state, d_c2 = 750, Fa = 0.71.
    scene["reaction_diffusion"]["species"] = {
        "c1": {"initial": {"random": [0.1658, 0.1858]}},
        "c2": {"diffusion": 750, "initial": {"random": [0.2086, 0.2286]}},
        "C": {"initial": 9.25}}
    scene["reaction_diffusion"]["seed"] = 7
    scene["numbers"]["Fa"] = 0.71
    scene["output"] = {"every": 0, "progress": False, "checkpoints": {"every": 6, "keep": 3}}
    part = copy.deepcopy(scene)
    part["numerics"]["end_time"] = 0.006
    # The restart continues in the shorter run's directory (part): its rows against full's.
    full, continued, log = restart_from_shorter_run(scene, part, tmp_path)
    assert "restarting from" in log
    assert len(continued) == len(full)
    assert_same_observables(full, continued)


def check(scene, tmp_path):
    require_exe()
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene))
    return subprocess.run([EXE, "check", str(path)], capture_output=True, text=True, timeout=60)


def mutate(path, value):
    scene = cell_scene(flow=True)
    node = scene
    for key in path[:-1]:
        node = node.setdefault(key, {})
    node[path[-1]] = value
    return scene


RD = ["reaction_diffusion"]
BAD = [
    (RD + ["species", "c1", "diffusion"], -1, "reaction_diffusion.species.c1.diffusion"),
    (RD + ["kinetics"], {"a2": -160}, "reaction_diffusion.kinetics.a2"),
    (RD + ["kinetics"], {"b1": 0}, "reaction_diffusion.kinetics.b1"),
    (RD + ["kinetics"], {"k9": 1}, "k9"),
    (RD + ["species", "c1", "region"], "cytosol", "\"cytosol\" is not a region"),
    (RD + ["species", "C", "region"], "membrane", "C lives in the bulk"),
    (RD + ["species", "c3"], {"diffusion": 1}, "c3"),
    (RD + ["species", "c1", "initial"], {"value": 1, "where": "x >"}, "where"),
    (RD + ["species", "c2", "initial"], {"random": [0.3, 0.1]}, "low <= high"),
    (RD + ["chemotaxis"], {"mode": "rotating"}, "omega"),
    (RD + ["chemotaxis"], {"mode": "random_turns", "omega": 30}, "theta"),
    (RD + ["chemotaxis"], {"mode": "point_source"}, "x0"),
    (RD + ["chemotaxis"], {"mode": "point_source", "x0": [0, 0]}, "inside the domain"),
    (RD + ["chemotaxis"], {"mode": "spiral"}, "spiral"),
    (["numbers", "Fa"], 0, "numbers.Fa"),
    (RD + ["petsc"], {"ksp_type": ["gmres"]}, "reaction_diffusion.petsc.ksp_type"),
    (RD + ["petsc"], {"-ksp_type": "gmres"}, "without the leading '-'"),
]


@pytest.mark.parametrize("path,value,named", BAD, ids=[b[2] for b in BAD])
def test_bad_reaction_diffusion_input_stops_before_step_one_naming_it(tmp_path, path, value, named):
    proc = check(mutate(path, value), tmp_path)
    print(proc.stderr.strip())
    assert proc.returncode != 0
    assert "error:" in proc.stderr and named in proc.stderr
    assert "Traceback" not in proc.stderr and "terminate" not in proc.stderr


def test_units_give_the_active_surface_force_number(tmp_path):
    scene = cell_scene(flow=True)
    del scene["numbers"]
    # Table 5.1: Fa = eta V / (alpha L) = 10 * 0.14e-6 / (5.6 * 5e-6) = 0.05 (5.8)
    scene["units"] = {"length": 5e-6, "velocity": 0.14e-6, "density": 1e3, "viscosity": 10,
                      "bending_rigidity": 1e-17, "surface_tension": 5e-6,
                      "protrusion_coefficient": 5.6}
    proc = check(scene, tmp_path)
    assert proc.returncode == 0, proc.stderr
    numbers = dict(re.findall(r"(Re|Ca|Be|Fa) = ([0-9.e+-]+)", proc.stdout))
    # The thesis rounds: Be = 6.6, Ca = 0.264 (section 5.2.4).
    assert float(numbers["Ca"]) == pytest.approx(0.264, rel=1e-4)
    assert float(numbers["Be"]) == pytest.approx(6.6, rel=1e-4)
    assert float(numbers["Fa"]) == pytest.approx(0.05, rel=1e-12)
    assert "-(1/Fa) c1 grad phi with Fa = 0.05" in proc.stdout


def test_the_pattern_converges_as_epsilon_and_h_are_refined_together(tmp_path):
    # The half-loaded circle at t = 0.1, epsilon halved twice with 4 mesh points across the
    # interface each time (h ~ epsilon), dt fixed. Measured with a fourth member
    # (epsilon 0.025): the membrane amount changes by 6.4e-3, 1.6e-3, 9.9e-5 (rates 2.0,
    # 4.0), the largest c1 by 3.5e-3, 1.2e-3, 3.2e-4 (rates 1.5, 1.9).
    runs = {}
    for eps in [0.2, 0.1, 0.05]:
        work = tmp_path / f"eps{eps}"
        work.mkdir()
        runs[eps] = run_scene(cell_scene(epsilon=eps, end_time=0.1), work)
    for key in ["rd_mass_membrane", "rd_c1_max"]:
        q = [runs[eps][key][-1] for eps in [0.2, 0.1, 0.05]]
        d1, d2 = abs(q[0] - q[1]), abs(q[1] - q[2])
        rate = math.log2(d1 / d2)
        print(f"{key}: {q}, differences {d1:.2e} {d2:.2e}, rate {rate:.2f}")
        assert rate > 1.2, f"{key} converges at rate {rate:.2f}"


def test_a_rotating_signal_turns_the_front_with_it(tmp_path):
    # Mode 1 of section 5.4.3 on the frozen circle from the homogeneous state: grad c~ =
    # xi (cos wt, sin wt) with xi = 5 dominates the kinetics, so the c1 maximum points along
    # the signal (measured: 3-7 degrees behind it while it turns at 1.5 rad per unit time).
    scene = cell_scene(end_time=0.4)
    scene["reaction_diffusion"]["species"] = {"c1": {"initial": 0.1758},
                                              "c2": {"initial": 0.2186}, "C": {"initial": 9.25}}
    scene["reaction_diffusion"]["chemotaxis"] = {"mode": "rotating", "xi": 5, "omega": 1.5}
    c = run_scene(scene, tmp_path)
    for t, angle, logged in zip(c["time"], c["rd_c1_max_angle_deg"], c["rd_signal_angle_deg"]):
        signal = math.degrees(1.5 * t)
        assert abs(math.remainder(logged - signal, 360)) < 1e-6, f"t = {t}: signal logged at {logged}"
        if t >= 0.1:
            assert abs(angle - signal) < 10, f"t = {t}: c1 max at {angle:.1f}, signal at {signal:.1f}"
    print(f"t = {c['time'][-1]}: c1 max at {c['rd_c1_max_angle_deg'][-1]:.1f} deg, "
          f"signal at {math.degrees(1.5 * c['time'][-1]):.1f} deg")


def test_random_turns_of_the_signal_happen_every_theta_steps_by_plus_minus_omega(tmp_path):
    # Mode 3 of section 5.4.3: every theta steps the direction of grad c~ turns by -omega, 0
    # or omega, drawn from the seed; rd_signal_angle_deg logs it.
    scene = cell_scene(end_time=0.2)
    scene["reaction_diffusion"]["chemotaxis"] = {"mode": "random_turns", "omega": 30,
                                                 "theta": 4, "direction": 10}
    c = run_scene(scene, tmp_path)
    angles = c["rd_signal_angle_deg"]
    assert abs(angles[0] - 10) < 1e-9
    turns = []
    for step, before, after in zip(c["step"][1:], angles, angles[1:]):
        turn = math.remainder(after - before, 360)
        if int(step) % 4:
            assert abs(turn) < 1e-9, f"step {step}: turned by {turn} between turns"
        else:
            assert min(abs(turn - t) for t in (-30, 0, 30)) < 1e-9, f"step {step}: turn {turn}"
            turns.append(round(turn))
    print(f"turns every 4 steps: {turns}")
    assert len(turns) == 10 and len(set(turns)) > 1


def test_two_ranks_agree_with_one_with_random_initial_data(tmp_path):
    # Random values hash the snapped node position (not the rank's dof order), and "x > 0"
    # is decided on snapped coordinates, so both runs start from the same fields.
    scene = cell_scene(dt=1e-3, end_time=0.012, frozen=False, flow=True)
    scene["numerics"]["mesh"]["remesh_every"] = 4
    scene["reaction_diffusion"]["species"]["c1"] = {"initial": {"random": [0.1658, 0.1858]}}
    worst, _, _ = one_rank_against_two(scene, tmp_path)
    key = max(worst, key=worst.get)
    print(f"largest difference 1 rank against 2: {worst[key]:.1e} ({key}); "
          f"rd_mass {worst['rd_mass']:.1e}")
    # The LU factors sum in another order on two ranks: the multipliers, which are solved
    # for, differ most (1.4e-9 measured); the fields and amounts by ~1e-13.
    assert worst["rd_mass"] < 1e-12 and worst["rd_mass_membrane"] < 1e-10
    assert worst[key] < 1e-7


def test_fa_without_the_species_or_the_flow_is_refused(tmp_path):
    # numbers.Fa scales the protrusion force of reaction_diffusion on the flow: a scene
    # without one of them would not use it.
    for drop in ["flow", "reaction_diffusion"]:
        scene = cell_scene(flow=True)
        del scene[drop]
        proc = check(scene, tmp_path)
        assert proc.returncode == 2 and "numbers.Fa" in proc.stderr, proc.stderr
        assert ("no flow" if drop == "flow" else "no reaction_diffusion") in proc.stderr


def test_reused_factorisations_give_the_direct_solves_observables(tmp_path):
    # numerics.solver: reuse keeps the factors of an earlier matrix as the preconditioner of
    # GMRES (relative residual 1e-10) for the flow, the phase field and the species, and
    # factorises again when a solve needs more than 8 iterations.
    scene = cell_scene(dt=1e-3, end_time=0.012, frozen=False, flow=True)
    scene["numerics"]["mesh"]["remesh_every"] = 6
    runs = {}
    for solver in ["direct", "reuse"]:
        scene["numerics"]["solver"] = solver
        (tmp_path / solver).mkdir()
        runs[solver] = run_scene(scene, tmp_path / solver)
    direct, reuse = runs["direct"], runs["reuse"]
    # Measured: 1e-9 (x_cm, c1), 8e-8 (Helfrich energy), 5e-7 (v_cm, a flow solved to a
    # residual of 1e-10 of a right-hand side dominated by the interface force).
    for key, tol in [("center_x", 1e-7), ("rd_c1_max", 1e-7), ("helfrich_energy", 1e-6),
                     ("cell_velocity_x", 1e-5), ("volume", 1e-10), ("rd_mass", 1e-9)]:
        diff = max(abs(a - b) / max(1.0, abs(a)) for a, b in zip(direct[key], reuse[key]))
        print(f"{key}: reuse against direct {diff:.1e}")
        assert diff < tol, key
    iterations = reuse["rd_krylov_iterations"][1:]
    print(f"species: {reuse['rd_factorisations'][-1]:.0f} factorisations in "
          f"{len(iterations)} steps, GMRES iterations per step {iterations}")
    assert reuse["rd_factorisations"][-1] < direct["rd_factorisations"][-1]
    assert max(iterations) <= 30


def test_a_point_source_draws_the_front_towards_it(tmp_path):
    # Mode 4 of section 5.4.3: grad c~ = -xi (x - x0)/|x - x0| with x0 outside the domain,
    # on the left of the frozen circle: the c1 maximum turns to face it (angle 180).
    scene = cell_scene(end_time=0.3)
    scene["reaction_diffusion"]["species"] = {"c1": {"initial": 0.1758},
                                              "c2": {"initial": 0.2186}, "C": {"initial": 9.25}}
    scene["reaction_diffusion"]["chemotaxis"] = {"mode": "point_source", "x0": [-6, 0]}
    c = run_scene(scene, tmp_path)
    angle = c["rd_c1_max_angle_deg"][-1]
    print(f"t = {c['time'][-1]}: c1 max at {angle:.1f} deg, min at "
          f"{c['rd_c1_min_angle_deg'][-1]:.1f} deg")
    assert abs(angle) > 170
    assert abs(c["rd_c1_min_angle_deg"][-1]) < 10
    assert abs(abs(c["rd_signal_angle_deg"][-1]) - 180) < 1e-6  # from the centre towards x0


def test_the_demo_plot_draws_the_fields_and_observables(tmp_path):
    # demos/gtpase-motile-cell/plot_cell.py reads the run with python/cellphase_results.py
    # (XDMF + HDF5) and draws the rows of Fig. 5.4 and the observables with matplotlib.
    scene = cell_scene(dt=1e-3, end_time=0.004, frozen=False, flow=True)
    scene["output"] = {"every": 2, "fields": ["phi", "c1", "c2", "C", "v"]}
    run_scene(scene, tmp_path)
    out = tmp_path / "out"
    script = Path(__file__).resolve().parents[2] / "demos" / "gtpase-motile-cell" / "plot_cell.py"
    proc = subprocess.run([sys.executable, str(script), str(out), "--times", "0", "0.004"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    for name in ["fig-5-4.png", "observables.png"]:
        image = matplotlib.image.imread(out / name)
        assert image.shape[0] > 300 and image.shape[1] > 300
        assert image[..., :3].std() > 0.05  # not a blank canvas


def test_the_chemotaxis_plot_draws_the_track_and_the_polarity(tmp_path):
    # demos/gtpase-chemotaxis/plot_chemotaxis.py reads the scene (mode, output directory),
    # the observables (rd_signal_angle_deg) and phi (XDMF + HDF5), and draws with matplotlib.
    scene = cell_scene(dt=1e-3, end_time=0.004, frozen=False, flow=True)
    scene["reaction_diffusion"]["chemotaxis"] = {"mode": "random_turns", "omega": 45, "theta": 2}
    scene["output"] = {"every": 2, "fields": ["phi"]}
    run_scene(scene, tmp_path)
    script = Path(__file__).resolve().parents[2] / "demos" / "gtpase-chemotaxis" / "plot_chemotaxis.py"
    proc = subprocess.run([sys.executable, str(script), str(tmp_path / "scene.yaml")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    for name in ["track.png", "polarity.png"]:
        image = matplotlib.image.imread(tmp_path / "out" / name)
        assert image.shape[0] > 300 and image.shape[1] > 300
        assert image[..., :3].std() > 0.05  # not a blank canvas


def test_species_solver_options_of_their_own(tmp_path):
    # reaction_diffusion.petsc gives the species' system its own solver (here GMRES with
    # block-Jacobi ILU(0), relative residual 1e-12) while the phase field stays direct.
    scene = cell_scene(dt=1e-3, end_time=0.005)
    runs = {}
    for name, petsc in [("direct", None), ("gmres", {"ksp_type": "gmres", "pc_type": "bjacobi",
                                                      "ksp_rtol": 1e-12, "ksp_max_it": 1000})]:
        if petsc:
            scene["reaction_diffusion"]["petsc"] = petsc
        (tmp_path / name).mkdir()
        runs[name] = run_scene(scene, tmp_path / name)
    direct, gmres = runs["direct"], runs["gmres"]
    iterations = gmres["rd_krylov_iterations"][1:]
    print(f"GMRES iterations per step {iterations}")
    assert min(iterations) > 0 and max(direct["rd_krylov_iterations"]) == 0
    # A residual of 1e-12 leaves the species (and their amount) within about 1e-10 of the
    # direct solve; the phase field is frozen, so the rest is equal.
    for key in ["rd_c1_max", "rd_c1_min", "rd_mass", "rd_mass_membrane"]:
        diff = max(abs(a - b) / max(1.0, abs(a)) for a, b in zip(direct[key], gmres[key]))
        print(f"{key}: GMRES against LU {diff:.1e}")
        assert diff < 1e-9, key


def test_species_solver_key_is_checked(tmp_path):
    # reaction_diffusion.solver picks direct or reused factorisations for the species alone.
    scene = cell_scene()
    scene["reaction_diffusion"]["solver"] = "reuse"
    assert check(scene, tmp_path).returncode == 0
    scene["reaction_diffusion"]["solver"] = "lu"
    proc = check(scene, tmp_path)
    assert proc.returncode == 2 and 'reaction_diffusion.solver: unknown value "lu"' in proc.stderr, \
        proc.stderr


def test_coupling_stabilisation_lets_the_motile_cell_take_steps_where_the_split_blows_up(
        tmp_path):
    """flow.coupling_stabilisation beta with the L2 flow: -beta (B^{n+1} - B^n) in the phase
    field's step, B the bending part of dE/dphi (forms/helfrich_l2.py). The flow takes the
    bending force explicitly, which limits dt to about eta h^3 Be: here (eps 0.1, h 0.0625)
    the plain split blows up at dt = 0.1, while beta = 0.02 (0.3 times the mobility) runs
    and keeps volume and GTPase amount. At a dt where both run, beta moves the cell by far
    less than the split's own time error."""
    def scene(dt, end_time, beta=None):
        s = cell_scene(dt=dt, end_time=end_time, frozen=False, flow=True)
        if beta is not None:
            s["flow"]["coupling_stabilisation"] = beta
        return s

    runs = {}
    for name, dt, end_time, beta in [("plain", 0.1, 2.0, None), ("stabilised", 0.1, 2.0, 0.02),
                                     ("plain_0.04", 0.04, 0.8, None),
                                     ("stabilised_0.04", 0.04, 0.8, 0.02)]:
        (tmp_path / name).mkdir()
        if name == "plain":
            with pytest.raises(AssertionError, match="numerical failure in the phase-field"):
                run_scene(scene(dt, end_time, beta), tmp_path / name)  # step 17: phi -2.9
            continue
        runs[name] = run_scene(scene(dt, end_time, beta), tmp_path / name)

    st = runs["stabilised"]
    volume = max(abs(v - st["volume"][0]) for v in st["volume"]) / st["volume"][0]
    mass = max(abs(m - st["rd_mass"][0]) for m in st["rd_mass"]) / st["rd_mass"][0]
    x, H = st["center_x"], st["helfrich_energy"]
    print(f"stabilised, dt 0.1: Helfrich energy {H[0]:.3f} -> {H[-1]:.3f}, x_cm {x[-1]:.4f}; "
          f"drift: volume {volume:.1e}, GTPase {mass:.1e}")
    assert volume < 1e-10 and mass < 1e-12
    assert all(b > a for a, b in zip(x[1:], x[2:])), "the cell does not move steadily in +x"
    assert max(H) < 2 * H[0]  # 0.469 -> 0.687 as the cell polarises
    # Both at dt = 0.04, t = 0.8: x_cm 1.2e-3 and Helfrich energy 6.3e-4 apart (at t = 1.2:
    # 7e-4 and 5e-3), while the plain split's x_cm at t = 1.2 moves by 0.15 between
    # dt = 0.02 and 0.04 (first order in dt): beta's O(dt) term is the smaller error.
    a, b = runs["plain_0.04"], runs["stabilised_0.04"]
    dx = abs(b["center_x"][-1] - a["center_x"][-1]) / a["center_x"][-1]
    dH = abs(b["helfrich_energy"][-1] - a["helfrich_energy"][-1]) / a["helfrich_energy"][-1]
    print(f"dt 0.04, t = {a['time'][-1]}: beta 0.02 against the plain split: x_cm {dx:.1e}, "
          f"Helfrich energy {dH:.1e}")
    assert dx < 5e-3 and dH < 2e-2
