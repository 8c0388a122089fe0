"""Every phase-field model is a gradient flow: with the thesis' Taylor linearisation its
energy must not increase, and its constraints must hold to the stated tolerances, with
either time scheme.
Fixed mesh (no remeshing), an ellipse with semi-axes 1.2 x 0.7, eps = 0.08, 20 steps."""
import pytest

from conftest import assert_same_as_lu, circle_scene, run_scene

# model, boundary of phi, relative tolerance on the volume, on the membrane length
CASES = [
    # L2 flows: Allen-Cahn moves by curvature (no constraint).
    ("allen_cahn", "dirichlet", None, None),
    # explicit multiplier (2.27) with the drift relaxed over two steps: O(dt^2) per step
    ("allen_cahn_volume", "dirichlet", 1e-4, None),
    # H^-1 flows with natural boundary conditions conserve int phi to round-off
    ("cahn_hilliard", "neumann", 1e-10, None),
    # multipliers at t^{n+1}: volume is linear (round-off), the area is linearised
    # about phi^n, so it holds to O(|phi^{n+1} - phi^n|^2) (seen 1.5e-5)
    ("helfrich_lagrange", "dirichlet", 1e-10, 1e-4),
    # penalties p = 1000 hold the constraints to O(force / p) (seen 3.7e-4 and 5.1e-4)
    ("helfrich_penalty", "dirichlet", 1e-3, 1e-3),
    # H^-1: volume to round-off; area penalty p2 = 1000 (seen 4.6e-4)
    ("helfrich_hm1", "neumann", 1e-10, 1e-3),
]


# numerics.time_scheme: euler (the thesis') and bdf2 (not for allen_cahn_volume)
SCHEMES = [(*case, scheme) for case in CASES for scheme in ("euler", "bdf2")
           if not (case[0] == "allen_cahn_volume" and scheme == "bdf2")]


@pytest.mark.parametrize("model,boundary,vol_tol,area_tol,scheme", SCHEMES)
def test_energy_decays_and_constraints_hold(tmp_path, model, boundary, vol_tol, area_tol,
                                            scheme):
    scene = circle_scene(model, epsilon=0.08, end_time=0.02, dt=1e-3, time_scheme=scheme)
    scene["boundary"] = {"phi": boundary}
    scene["cells"] = [{"shape": "ellipse", "center": [0, 0], "semi_axes": [1.2, 0.7]}]
    if model in ("helfrich_penalty", "helfrich_hm1"):
        scene["phase_field"].update({"penalty_volume": 1000, "penalty_area": 1000})
    obs = run_scene(scene, tmp_path)
    energy, volume, length = obs["total_energy"], obs["volume"], obs["surface"]

    increases = [b - a for a, b in zip(energy, energy[1:])]
    # Round-off of the assembled energy is ~1e-14 relative; allow 1e-12.
    assert max(increases) <= 1e-12 * abs(energy[0]), f"energy rose by {max(increases):.3e}"
    assert energy[-1] < energy[0]

    if vol_tol is not None:
        drift = max(abs(v - volume[0]) for v in volume) / volume[0]
        assert drift < vol_tol, f"volume drift {drift:.3e}"
    if area_tol is not None:
        drift = max(abs(a - length[0]) for a in length) / length[0]
        assert drift < area_tol, f"length drift {drift:.3e}"


@pytest.mark.parametrize("model", ["helfrich_hm1", "helfrich_lagrange"])
def test_surface_tension_adds_its_energy_and_shortens_the_membrane(tmp_path, model):
    """phase_field.surface_tension adds (1/Ca) E_CH to the Helfrich energy, (3.77)-(3.78):
    the force (1/Ca) kappa of (3.84)/(3.87) is explicit in kappa, like the area penalty.
    The energy with it must decay. The membrane, free to shrink (no area penalty;
    helfrich_lagrange with surface tension keeps only the volume multiplier, (3.83)-(3.85)),
    must lose more than twice the length it loses without (hm1 without: bending alone;
    lagrange without: the area multiplier holds it)."""
    runs = {}
    for tension in (False, True):
        scene = circle_scene(model, epsilon=0.08, end_time=0.02, dt=1e-3)
        scene["boundary"] = {"phi": "neumann" if model == "helfrich_hm1" else "dirichlet"}
        scene["cells"] = [{"shape": "ellipse", "center": [0, 0], "semi_axes": [1.2, 0.7]}]
        scene["phase_field"]["surface_tension"] = tension
        scene["numbers"] = {"Ca": 0.1}
        (tmp_path / str(tension)).mkdir()
        runs[tension] = run_scene(scene, tmp_path / str(tension))
    obs = runs[True]
    energy = obs["total_energy"]
    # total = Helfrich + (1/Ca) E_CH (no penalties here)
    assert energy[0] == pytest.approx(obs["helfrich_energy"][0] + 10 * obs["energy_ch"][0],
                                      rel=1e-12)
    increases = [b - a for a, b in zip(energy, energy[1:])]
    assert max(increases) <= 1e-12 * abs(energy[0]), f"energy rose by {max(increases):.3e}"
    shrink = {t: r["surface"][0] - r["surface"][-1] for t, r in runs.items()}
    print(f"{model}: length lost with tension {shrink[True]:.3e}, without {shrink[False]:.3e}")
    assert shrink[True] > 2 * abs(shrink[False])


@pytest.mark.parametrize("model", ["helfrich_lagrange", "helfrich_penalty"])
def test_stabilised_symmetric_factorisation_equals_lu(tmp_path, model):
    """The stabilised L2 Helfrich matrix is made symmetric by scaling its phi rows
    (row_psi = -eps Be / gamma, forms/helfrich_l2.py) and factorised as L D L^T. The same
    scheme solved with LU (pc_type lu from the scene) must give the same observables: both
    are direct solves of one linear system, so they differ by round-off only (seen 3e-12
    for the Helfrich energy, 7e-15 for the others; asserted 1e-9 relative to
    max(1, |value|)). The energy of the stabilised scheme must still decay."""
    runs = {}
    for pc in ("default", "lu"):
        scene = circle_scene(model, epsilon=0.08, end_time=0.02, dt=1e-3)
        scene["boundary"] = {"phi": "dirichlet"}
        scene["cells"] = [{"shape": "ellipse", "center": [0, 0], "semi_axes": [1.2, 0.7]}]
        scene["numerics"]["linearisation"] = "stabilised"
        scene["numerics"]["mesh"]["remesh_every"] = 10  # a new factorisation on each mesh
        if model == "helfrich_penalty":
            scene["phase_field"].update({"penalty_volume": 1000, "penalty_area": 1000})
        if pc == "lu":
            scene["numerics"]["petsc"] = {"pc_type": "lu"}
        (tmp_path / pc).mkdir()
        runs[pc] = run_scene(scene, tmp_path / pc)
    assert_same_as_lu(runs, ("helfrich_energy", "volume", "surface", "center_x"))
    energy = runs["default"]["total_energy"]
    assert energy[-1] < energy[0]
