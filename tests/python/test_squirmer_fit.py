"""python/squirmer_fit.py (thesis section 6.5) on synthetic profiles, fields and meshes."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from conftest import write_vtk_run

PYTHON_DIR = Path(__file__).resolve().parents[2] / "python"
SCRIPT = PYTHON_DIR / "squirmer_fit.py"
sys.path.insert(0, str(PYTHON_DIR))
from squirmer_fit import (cell_centre_and_velocity, far_field, far_field_samples,  # noqa: E402
                          fit_far_field, fit_squirmer_profile, plot_far_field, plot_profile,
                          squirmer_profile, tangential_profile)

TABLE_6_3 = [(0.0294, 0.0387, -0.3541, 12.5882), (0.1089, 0.1460, 0.3910, 47.3611)]


def square_mesh(n, half_width):
    """Structured triangle mesh of [-w, w]^2, n x n squares each cut in two."""
    x = np.linspace(-half_width, half_width, n + 1)
    X, Y = np.meshgrid(x, x)
    points = np.column_stack([X.ravel(), Y.ravel()])
    i, j = np.meshgrid(np.arange(n), np.arange(n))
    a = (j * (n + 1) + i).ravel()
    b, c, d = a + 1, a + n + 1, a + n + 2
    cells = np.concatenate([np.column_stack([a, b, d]), np.column_stack([a, d, c])])
    return points, cells


def circle_phi(points, centre, radius=5.0, eps=0.2):
    r = np.linalg.norm(points - centre, axis=1)
    return np.tanh((radius - r) / (np.sqrt(2) * eps))


def polar(points, centre):
    rel = points - centre
    alpha = np.arctan2(rel[:, 1], rel[:, 0])
    return alpha, np.column_stack([-np.sin(alpha), np.cos(alpha)])


@pytest.mark.parametrize("n1, m", [(0.172, 0.059), (0.291, -0.139)])
def test_profile_fit(n1, m):
    alpha = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    exact = squirmer_profile(alpha, n1, m)
    assert np.allclose(fit_squirmer_profile(alpha, exact), (n1, m), rtol=0, atol=1e-12)
    noisy = exact + 0.01 * n1 * np.random.default_rng(6).standard_normal(alpha.size)
    n1_fit, m_fit = fit_squirmer_profile(alpha, noisy)
    assert abs(n1_fit - n1) < 0.02 * n1 and abs(m_fit - m) < 0.01


def test_profile_fit_refuses():
    with pytest.raises(ValueError, match="at least 3 samples"):
        fit_squirmer_profile([0.1, 0.2], [1.0, 2.0])
    alpha = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    with pytest.raises(ValueError, match="n1 is 0"):
        fit_squirmer_profile(alpha, np.zeros_like(alpha))


def test_far_field_formula():
    """Eq. (6.19) by hand on the axes: rhat rhat^T e1 is e1 on the x axis, 0 on the y axis."""
    v, st, str_, sd = 0.3, 0.7, 1.1, 2.3
    r = 2.0
    u = far_field(np.array([[r, 0.0], [0.0, r], [-r, 0.0]]), v, st, str_, sd)
    on_axis = -v - 2 * st / r + 2 * str_ / r**2 + (2 / 3) * sd / r**3
    assert np.allclose(u[0], [on_axis, 0])
    assert np.allclose(u[1], [-v - st / r - sd / (3 * r**3), -str_ / r**2])
    # The stresslet is odd in x, the other modes even.
    assert np.allclose(u[2], [on_axis - 4 * str_ / r**2, 0])


@pytest.mark.parametrize("coeffs", TABLE_6_3)
def test_far_field_fit(coeffs):
    x, y = np.meshgrid(np.linspace(-40, 40, 161), np.linspace(-20, 20, 81))
    points = np.column_stack([x.ravel(), y.ravel()])
    velocities = far_field(points[np.linalg.norm(points, axis=1) > 5], *coeffs)
    # Points inside r = 5 get rubbish that the fit must ignore.
    inside = np.linalg.norm(points, axis=1) <= 5
    full = np.empty_like(points)
    full[~inside] = velocities
    full[inside] = 1e3
    fit = fit_far_field(points, full, radius=5.0)
    assert np.allclose([fit[k] for k in ("v_cell", "A_st", "A_str", "A_sd")], coeffs,
                       rtol=1e-9, atol=0)


def test_far_field_fit_refuses_no_points():
    with pytest.raises(ValueError, match="outside r = 5"):
        fit_far_field(np.array([[1.0, 0.0], [0.0, 2.0]]), np.zeros((2, 2)))


@pytest.fixture(scope="module")
def mesh():
    return square_mesh(140, 10.0)  # h = 1/7: interpolation errors ~2e-4 on n1 and m


@pytest.mark.parametrize("n1, m", [(0.172, 0.059), (0.291, -0.139)])
def test_tangential_profile(mesh, n1, m):
    points, cells = mesh
    centre, v_cell = np.array([0.3, -0.2]), 0.05
    phi = circle_phi(points, centre)
    alpha, e_alpha = polar(points, centre)
    v = squirmer_profile(alpha, n1, m)[:, None] * e_alpha + [v_cell, 0.0]
    a, vT = tangential_profile(points, cells, phi, v, centre, v_cell)
    assert np.all(np.diff(a) >= 0) and a.min() >= 0 and a.max() < 2 * np.pi and len(a) > 100
    n1_fit, m_fit = fit_squirmer_profile(a, vT)
    assert abs(n1_fit - n1) < 1e-3 and abs(m_fit - m) < 1e-3


def test_sign_convention(mesh):
    """A cell swimming in +x through fluid at rest: in its frame the fluid streams from
    front to rear, so n1 > 0. And Blake's squirmer, u_theta = B1 sin(theta) +
    B2 sin(theta) cos(theta) along e_theta (theta from the swimming direction, e_theta
    pointing from the front to the rear), gives n1 = B1 and m = B2 / 2 (a puller, B2 > 0,
    has m > 0)."""
    points, cells = mesh
    centre = np.zeros(2)
    phi = circle_phi(points, centre)
    U = 0.1
    a, vT = tangential_profile(points, cells, phi, np.zeros_like(points), centre, U)
    n1, m = fit_squirmer_profile(a, vT)
    assert abs(n1 - U) < 1e-3 and abs(m) < 1e-3

    B1, B2 = 0.2, 0.12
    rel = points - centre
    theta = np.arccos(np.clip(rel[:, 0] / np.maximum(np.linalg.norm(rel, axis=1), 1e-300),
                              -1, 1))
    e_theta = np.column_stack([-np.sin(theta), np.where(rel[:, 1] >= 0, 1, -1) * np.cos(theta)])
    v = (B1 * np.sin(theta) + B2 * np.sin(theta) * np.cos(theta))[:, None] * e_theta
    n1, m = fit_squirmer_profile(*tangential_profile(points, cells, phi, v, centre, 0.0))
    assert abs(n1 - B1) < 1e-3 and abs(m - B2 / (2 * B1)) < 1e-3


def test_tangential_profile_without_level_set(mesh):
    points, cells = mesh
    with pytest.raises(ValueError, match="no zero level set"):
        tangential_profile(points, cells, -np.ones(len(points)), np.zeros_like(points),
                           (0, 0), 0.0)


def test_far_field_samples_and_centre(mesh):
    points, cells = mesh
    centre = np.array([1.0, -0.5])
    phi = circle_phi(points, centre, radius=3.0, eps=0.1)
    v = np.column_stack([0.2 * np.ones(len(points)), points[:, 0], np.zeros(len(points))])
    found, v_cell = cell_centre_and_velocity(points, cells, phi, v)
    assert np.allclose(found, centre, atol=1e-4) and abs(v_cell - 0.2) < 1e-12
    x, u = far_field_samples(points, phi, v, centre, 0.2, 5.0)
    expect = np.linalg.norm(points - centre, axis=1) > 5.0
    assert len(x) == expect.sum()
    assert np.allclose(x, points[expect] - centre)
    assert np.allclose(u, np.column_stack([np.zeros(expect.sum()), points[expect, 0]]))


def test_plots(tmp_path):
    alpha = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    plot_profile(alpha, squirmer_profile(alpha, 0.2, 0.1), 0.2, 0.1, tmp_path / "profile.png")
    x, y = np.meshgrid(np.linspace(-20, 20, 21), np.linspace(-10, 10, 11))
    points = np.column_stack([x.ravel(), y.ravel()])
    points = points[np.linalg.norm(points, axis=1) > 5]
    coeffs = dict(zip(("v_cell", "A_st", "A_str", "A_sd"), TABLE_6_3[0]))
    plot_far_field(points, far_field(points, *TABLE_6_3[0]), coeffs, tmp_path / "far.png")
    for name in ("profile.png", "far.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def squirmer_fit(*args):
    return subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=60)


def test_cli_missing_directory(tmp_path):
    missing = tmp_path / "no-such-run"
    result = squirmer_fit(missing)
    assert result.returncode == 2
    assert str(missing) in result.stderr and "Traceback" not in result.stderr


def test_cli_on_a_run(tmp_path):
    """The command line reads phi and v, and prints what the functions give on them."""
    points, cells = square_mesh(60, 15.0)
    centre = np.array([0.4, 0.3])
    phi = circle_phi(points, centre, radius=4.0, eps=0.4)
    alpha, e_alpha = polar(points, centre)
    v = squirmer_profile(alpha, 0.17, 0.06)[:, None] * e_alpha + [0.03, 0.0]
    v3 = np.column_stack([v, np.zeros(len(points))])  # DOLFINx pads 2D vectors to 3
    write_vtk_run(tmp_path / "run", points, cells, {"phi": phi, "v": v3})
    result = squirmer_fit(tmp_path / "run", "--plot", tmp_path / "p.png")
    assert result.returncode == 0, result.stderr
    printed = dict(line.split(" = ") for line in result.stdout.splitlines())
    assert set(printed) == {"time", "n1", "m", "v_cell", "v_cell_fit", "A_st", "A_str", "A_sd"}
    assert float(printed["time"]) == 2.5
    c, v_cell = cell_centre_and_velocity(points, cells, phi, v)
    n1, m = fit_squirmer_profile(*tangential_profile(points, cells, phi, v, c, v_cell))
    fit = fit_far_field(*far_field_samples(points, phi, v, c, v_cell, 5.0), 5.0)
    for name, value in {"n1": n1, "m": m, "v_cell": v_cell, "v_cell_fit": fit["v_cell"],
                        "A_st": fit["A_st"], "A_sd": fit["A_sd"]}.items():
        assert float(printed[name]) == pytest.approx(value, rel=1e-5, abs=1e-12), name
    assert (tmp_path / "p.png").stat().st_size > 0


def test_cli_missing_field(tmp_path):
    points, cells = square_mesh(4, 10.0)
    write_vtk_run(tmp_path / "run", points, cells, {"phi": circle_phi(points, (0, 0))})
    result = squirmer_fit(tmp_path / "run", "--velocity", "u")
    assert result.returncode == 2 and "'u'" in result.stderr and "Traceback" not in result.stderr
