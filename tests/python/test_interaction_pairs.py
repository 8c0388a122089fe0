"""Interaction numbers and potentials per pair of cells (thesis (7.5), (7.11) with In_ij):
`interaction.pairs` gives some pairs an In or a potential of their own; the others keep
the scene's. Circles of the H^-1 Helfrich flow whose diffuse bands overlap, no flow."""
import pytest
import yaml

from conftest import run_scene
from test_many_cells import TWO, check

LJ = {"potential": "lennard_jones", "r1": 2, "r2": 1, "a1": 1, "a2": 0, "a3": 20}  # Fig. 7.7

# Three circles in a row, each band overlapping its neighbour's.
THREE = yaml.safe_load(yaml.safe_dump(TWO))
THREE["domain"] = {"lower": [-1.4, -0.6], "upper": [1.4, 0.6], "resolution": [28, 12]}
THREE["cells"] = [{"name": n, "shape": "circle", "center": [x, 0], "radius": 0.3}
                  for n, x in [("left", -0.66), ("mid", 0.0), ("right", 0.66)]]


def with_interaction(base, interaction):
    scene = yaml.safe_load(yaml.safe_dump(base))
    if interaction:
        scene["interaction"] = interaction
    return scene


def largest_difference(a, b, keys):
    """max over keys and rows of |a - b| / max(1, |b|)."""
    return {k: max(abs(x - y) / max(1.0, abs(y)) for x, y in zip(a[k], b[k])) for k in keys}


COMPARED = ["left.center_x", "right.center_x", "left.volume", "right.volume",
            "overlap_max", "interaction_energy", "total_energy"]


@pytest.mark.parametrize("name, by_pair, scene_wide", [
    # In_ij = 1 for the one pair against In = 1 for the scene: the pair's In enters the sums
    # as In / In_ij = 3 and the forms' 1/In = 1/3, in another order of round-off.
    ("In", {"In": 3.0, "pairs": [{"cells": ["left", "right"], "In": 1.0}]}, {"In": 1.0}),
    # The Lennard-Jones-like potential for the one pair against it for the scene: the
    # scene's repulsive potential then has a source of its own whose sums stay zero.
    # (In = 30: at In = 1 and 10 the adhesion of these overlapping bands breaks step 2.)
    ("potential", {"In": 30.0, "refresh": True, "pairs": [{"cells": ["left", "right"], **LJ}]},
     {"In": 30.0, "refresh": True, **LJ}),
])
def test_a_pair_of_its_own_is_the_scene_wide_interaction_for_that_pair(
        tmp_path, name, by_pair, scene_wide):
    (tmp_path / "pair").mkdir()
    (tmp_path / "scene").mkdir()
    a = run_scene(with_interaction(TWO, by_pair), tmp_path / "pair")
    b = run_scene(with_interaction(TWO, scene_wide), tmp_path / "scene")
    diff = largest_difference(a, b, COMPARED)
    print(f"{name} per pair against scene-wide: " + ", ".join(f"{k} {v:.1e}" for k, v in diff.items()))
    assert abs(a["interaction_energy"][0]) > 0.01  # the potential acts from the first step
    # Same equations; the summation order differs (3 * w / 3, or a zero source added), so
    # they agree to round-off amplified over 12 steps; 1e-10 leaves a factor 100 to spare.
    assert max(diff.values()) < 1e-10, diff


@pytest.fixture(scope="module")
def row_of_three(tmp_path_factory):
    out = {}
    for name, interaction in [
        ("free", None),
        ("all", {"In": 1.0}),
        # mid-right: In_ij = 1e8, its interaction 1e-8 of the others'
        ("selective", {"In": 1.0, "pairs": [{"cells": ["mid", "right"], "In": 1e8}]}),
    ]:
        out[name] = run_scene(with_interaction(THREE, interaction), tmp_path_factory.mktemp(name))
    return out


def test_only_the_pairs_that_interact_push_each_other(row_of_three):
    free, all_, sel = row_of_three["free"], row_of_three["all"], row_of_three["selective"]

    def shift(run, cell):
        return run[f"{cell}.center_x"][-1] - free[f"{cell}.center_x"][-1]

    pushed = shift(all_, "left")
    print(f"left pushed by {pushed:.3e} (all pairs), {shift(sel, 'left'):.3e} (mid-right "
          f"weakened); right {shift(all_, 'right'):.3e}, {shift(sel, 'right'):.3e}; mid "
          f"{shift(all_, 'mid'):.3e}, {shift(sel, 'mid'):.3e}")
    # With every pair interacting the row spreads symmetrically: right moves as left does,
    # mirrored, and mid stays. The refined meshes are not exact mirror images (mid moves
    # 1.2e-4, the two ends differ by 0.7 % of their shift), so the bounds are 2 % and 1 %.
    assert pushed < -0.01
    assert abs(shift(all_, "right") + pushed) < 0.02 * abs(pushed)
    assert abs(shift(all_, "mid")) < 0.01 * abs(pushed)
    # With mid-right weakened 1e8-fold, right moves as without any potential (its only
    # neighbour is mid; left is 18 eps away, where w_left is below 1e-60): 1.5e-5 of the
    # push measured, from the meshes, which follow mid; the bound is 1e-4. Left and mid push
    # each other apart, each about as far (measured 1.5 %, bound 5 %), and left less far
    # than when mid was held by right (74 % measured; bounds 50 % and 100 %).
    assert abs(shift(sel, "right")) < 1e-4 * abs(pushed)
    assert abs(shift(sel, "mid") + shift(sel, "left")) < 0.05 * abs(shift(sel, "left"))
    assert pushed < shift(sel, "left") < 0.5 * pushed
    for cell in ["left", "mid", "right"]:
        v = sel[f"{cell}.volume"]
        assert max(abs(x - v[0]) for x in v) < 1e-10 * v[0]


@pytest.mark.parametrize("pairs, message", [
    ([{"cells": ["left", "nobody"], "In": 0.1}], 'names "nobody", which is no cell'),
    ([{"cells": ["left", "left"], "In": 0.1}], "names one phase field twice"),
    ([{"cells": ["left"], "In": 0.1}], "lists 1 names"),
    ([{"In": 0.1}], "interaction.pairs[0].cells"),
    ([{"cells": ["left", "right"], "In": 0.1}, {"cells": ["right", "left"], "In": 0.2}],
     "repeats the pair right, left"),
    ([{"cells": ["left", "right"], "In": -1}], "interaction.pairs[0].In"),
    ([{"cells": ["left", "right"], "a1": 1}], "interaction.pairs[0].a1"),
    ([{"cells": ["left", "right"], "potential": "lennard_jones", "r1": 2}], "interaction.pairs[0].r2"),
    ([{"cells": ["left", "right"], "strength": 2}], "strength"),
])
def test_bad_pairs_stop_before_the_first_step(tmp_path, pairs, message):
    proc = check(tmp_path, with_interaction(TWO, {"In": 0.1, "pairs": pairs}))
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "error:" in proc.stderr and message in proc.stderr, proc.stderr


def test_check_names_the_pairs_of_their_own(tmp_path):
    proc = check(tmp_path, with_interaction(
        THREE, {"In": 0.1, "pairs": [{"cells": ["mid", "right"], "In": 1}, {"cells": ["left", "mid"], **LJ}]}))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "2 pair(s) with In or potential of their own (2 potential(s)" in proc.stdout, proc.stdout


def test_derivative_reach_keeps_the_adhesive_potential_on_the_membranes(tmp_path):
    """interaction.derivative_reach: w'_i of (7.11) grows like e^(sqrt2 |d| / eps) away from
    cell i's membrane; the adhesion of Fig. 7.7b (a3 = 20) decays slower, so inside the
    other cell's band w'_i B(phi_j) is huge and moves phi_i there. Without a reach the two
    overlapping circles at In = 1 stop at step 2 (phi_left 15.6, beyond the bound 2); within
    3 epsilon of the membrane they run, phi stays in [-1.0002, 1] (measured -1.00015)."""
    scene = with_interaction(TWO, {"In": 1.0, "refresh": True, **LJ})
    (tmp_path / "unlimited").mkdir()
    with pytest.raises(AssertionError, match="phi_bound"):
        run_scene(scene, tmp_path / "unlimited")
    scene["interaction"]["derivative_reach"] = 3
    (tmp_path / "reach").mkdir()
    c = run_scene(scene, tmp_path / "reach")
    assert len(c["time"]) == 13  # all 12 steps
    assert min(c["phi_min"]) > -1.0002 and max(c["phi_max"]) < 1
    assert abs(c["interaction_energy"][0]) > 0.01
