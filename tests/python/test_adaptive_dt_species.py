"""Adaptive time step (numerics.adaptive_dt) with the sub-problems that carry fields of their
own: the GTPase species (reaction_diffusion) and the orientation field P (polar_gel). Each
estimates its own local time error by the extrapolation of its fields (core/
ExtrapolationEstimate), relative to max(1, the field's largest |value|); the step follows the
largest estimate of all sub-problems. A rejected step restores the species, P and the
estimates' u^{n-1}, and the species' copy of phi^n (their old transport weights): the total
GTPase amount, which only consistent weights keep to round-off, shows it. A restart continues
the step sequence bit for bit."""
import copy

import pytest

from conftest import run_scene
from test_checkpoint import assert_same_observables, run_and_restart
from test_gtpase import cell_scene
from test_polar_gel import gel_scene


def adaptive(scene, dt, tolerance):
    scene = copy.deepcopy(scene)
    scene["numerics"]["dt"] = dt
    scene["numerics"]["adaptive_dt"] = {"tolerance": tolerance}
    return scene


def column(table, key):
    return [float(r[key]) for r in table]


def test_motile_gtpase_cell_rejects_steps_keeps_its_amounts_and_restarts_bit_for_bit(tmp_path):
    """The motile cell of test_gtpase (flow, protrusion force, remeshes every 3 steps) from a
    first step of 1e-3 that the fast exchange of the half-loaded start makes far too large:
    the next steps are rejected and repeated smaller. Seen: 19 steps to t = 2e-3, 4 rejected.
    The total GTPase amount stays at round-off (the repeated step's old transport weight is
    phi^n again, not the rejected phi^{n+1}) and so does the volume."""
    scene = cell_scene(epsilon=0.15, dt=1e-3, end_time=2e-3, frozen=False, flow=True)
    scene["numerics"]["mesh"]["remesh_every"] = 3
    full, continued = run_and_restart(adaptive(scene, 1e-3, 1e-3), tmp_path, restart_step=12)
    rejected = column(full, "rejected_steps")
    print(f"{len(full) - 1} steps, {rejected[-1]:g} rejected")
    assert rejected[-1] >= 1
    assert len(full) > 16
    dts = column(full, "dt")[1:]
    assert min(dts) < 0.5 * max(dts)  # the steps follow the estimate
    estimates = column(full, "time_error")
    assert estimates[1] == -1 and max(estimates[2:]) <= 1e-3
    mass, volume = column(full, "rd_mass"), column(full, "volume")
    assert max(abs(m - mass[0]) for m in mass) < 1e-12 * mass[0]
    assert max(abs(v - volume[0]) for v in volume) < 1e-10 * volume[0]
    assert_same_observables(full, continued)


def test_frozen_pattern_steps_follow_the_species_alone(tmp_path):
    """The shape frozen (frozen_until), so the phase field makes no estimate: the species'
    estimate sets the steps, tiny in the fast exchange at the start and growing as the
    pattern settles. Seen (tolerance 1e-3, first step 1e-4, t = 0.02): about 100
    steps from 2.6e-6 to 1.4e-3, 19 rejected."""
    scene = adaptive(cell_scene(end_time=0.02), 1e-4, 1e-3)
    obs = run_scene(scene, tmp_path)
    dts, estimates = obs["dt"][1:], obs["time_error"]
    print(f"{len(dts)} steps from {min(dts):.2g} to {max(dts):.2g}, "
          f"{obs['rejected_steps'][-1]:g} rejected")
    assert min(dts) < 1e-5 and max(dts) > 5e-4
    assert max(estimates[2:]) <= 1e-3 and min(estimates[2:]) > 0
    assert obs["time"][-1] == pytest.approx(0.02, abs=1e-12)
    m = obs["rd_mass"]
    assert max(abs(x - m[0]) for x in m) < 1e-12 * m[0]


def test_passive_polar_gel_dissipates_every_accepted_step_and_restarts_bit_for_bit(tmp_path):
    """1/Fa = 0 from a first step of 1e-3: the orientation field's double well empties the
    outside fast, the estimate of P rejects steps there, and the energy (6.1) still falls
    at every accepted step, (6.10); the volume is kept to round-off. Seen: 14 steps to
    t = 5e-3, 4 rejected, energy 1480.2 -> 1339.7."""
    scene = gel_scene(dt=1e-3, end_time=0.005)
    scene["numerics"]["mesh"]["remesh_every"] = 5
    full, continued = run_and_restart(adaptive(scene, 1e-3, 1e-3), tmp_path, restart_step=8)
    energy, volume = column(full, "total_energy"), column(full, "volume")
    print(f"{len(full) - 1} steps, {column(full, 'rejected_steps')[-1]:g} rejected, "
          f"energy {energy[0]:.1f} -> {energy[-1]:.1f}")
    assert len(full) > 10
    assert max(b - a for a, b in zip(energy, energy[1:])) < 0
    assert max(abs(v - volume[0]) for v in volume) < 1e-12 * volume[0]
    assert max(column(full, "time_error")[2:]) <= 1e-3
    assert_same_observables(full, continued)
