"""Onset of motility of the active polar gel cell (thesis 6.4.2): below the critical
activity the cell comes to rest, well above it it moves with a speed that settles.

Both runs start from the same seed of the splay mode (`initial.splay`, a fan of divergence
0.1 inside a circle of radius 5) so that the instability does not have to grow from the
0.05 noise (which takes t ~ 300 at 1/Fa = 1.125, Fig. 6.5). The cell is the one of section
6.2.5 in a shorter channel (30 x 20, periodic in x, walls at the bottom and top) at the
thesis' coarsest epsilon = 0.42 (Table 6.2) with 3 points across the interface and a
refined interior; Table 6.1's numbers (Ca = 0.1, Be = 0.3, Pa = 1, xi = 1.1, kappa = 1.65).
The settings of the Table 6.2 study (benchmarks/studies/polar-convergence.yaml): the interior
one level coarser than the band, the orientation field on reused factors, METIS ordering
(1.4 times faster here than the demo's settings, the same speeds to 1-4 %).
The critical activity is about 0.75 at epsilon = 0.21 and grows with epsilon (Fig. 6.10);
1/Fa = 0.25 lies well below it and 1/Fa = 4 well above."""
from conftest import run_scene


def motility_scene(activity, end_time):
    return {
        "domain": {"lower": [0, 0], "upper": [30, 20], "resolution": [10, 7], "periodic": ["x"]},
        "cells": [{"shape": "circle", "center": [15, 10], "radius": 5}],
        "phase_field": {"model": "helfrich_hm1", "mobility": 0.025, "surface_tension": True},
        "numbers": {"Re": 0, "Ca": 0.1, "Be": 0.3, "Pa": 1},
        "flow": {},
        "polar_gel": {"activity": activity, "beta": 0,
                      "initial": {"direction": [1, 0], "noise": 0.05, "splay": 0.1,
                                  "inside_only": True, "seed": 1},
                      "solver": "reuse"},
        "numerics": {"epsilon": 0.42, "dt": 0.1, "end_time": end_time,
                     "mesh": {"points_across_interface": 3, "remesh_every": 10,
                              "inside_coarser_by": 1},
                     "petsc": {"mat_mumps_icntl_7": 5}},
    }


def window(columns, key, t0, t1):
    return [v for t, v in zip(columns["time"], columns[key]) if t0 <= t <= t1 + 1e-9]


def mean_speed(columns, t0, t1):
    v = [abs(x) for x in window(columns, "cell_velocity_x", t0, t1)]
    return sum(v) / len(v)


def test_below_the_critical_activity_the_cell_comes_to_rest(tmp_path):
    """1/Fa = 0.25: the seeded splay moves the cell at first (|v_cell| peaks at 5.8e-3 at
    t ~ 4) and then relaxes: from there on the speed falls at every step, to 2.5e-3 at
    t = 16 (an e-folding time of about 14). The first step's kick of the unrelaxed P^0
    (|v_cell| 0.07) is left out."""
    c = run_scene(motility_scene(0.25, 16), tmp_path)
    speed = [abs(v) for v in window(c, "cell_velocity_x", 2, 16)]
    peak, late = max(speed), mean_speed(c, 14, 16)
    assert peak > 2e-3, peak  # the seed does move the cell at first
    assert peak < 0.01, peak
    # at rest: no growth once the seed has relaxed (seen: it falls from t = 4.3 on) ...
    falling = [abs(v) for v in window(c, "cell_velocity_x", 5, 16)]
    assert all(b < a for a, b in zip(falling, falling[1:])), falling
    # ... and it has roughly halved by t = 16 (seen: 0.47 of the peak)
    assert late < 0.6 * peak, (peak, late)


def test_well_above_the_critical_activity_the_cell_moves_at_a_settling_speed(tmp_path):
    """1/Fa = 4: the splay grows, the cell accelerates from 0.118 (t ~ 8) to 0.298 (t ~ 20)
    and then moves at a constant speed, 0.212 from t = 28 on (the upper branch of Fig. 6.8;
    with the demo's finer interior and direct solves 0.211, and a seed of half the splay
    reaches the same speed ten time units later)."""
    c = run_scene(motility_scene(4, 32), tmp_path)
    late = window(c, "cell_velocity_x", 28, 32)
    mean = sum(late) / len(late)
    assert mean > 0.1, mean
    # Settled: over the last 4 time units the speed changes by less than 2 % of itself
    # (seen: 0.8 %), while it grew by more than half between t ~ 8 and t ~ 20.
    assert max(late) - min(late) < 0.02 * mean, (min(late), max(late))
    growth = max(window(c, "cell_velocity_x", 12, 24)) / min(window(c, "cell_velocity_x", 4, 10))
    assert growth > 1.5, growth
    # It travels along the initial orientation, as far as the speed says.
    x = c["center_x"]
    assert x[-1] - x[0] > 5.0, x[-1] - x[0]
    # The H^-1 flow keeps the volume (seen: 7e-14).
    v0 = c["volume"][0]
    assert max(abs(w - v0) for w in c["volume"]) < 1e-10 * v0
