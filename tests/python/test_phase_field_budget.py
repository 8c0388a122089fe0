"""python/phase_field_budget.py on fields in the VTK layout of the output: exact areas for a linear
phi, the circle's area to O(h^2), and the bulk's share of int (1 + phi)/2."""
import sys
from pathlib import Path

import numpy as np
from conftest import write_vtk_run

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
from phase_field_budget import budget  # noqa: E402


def square_mesh(n, size=2.0):
    """[0, size]^2 in n x n squares, each split into two triangles along alternating
    diagonals (so that no direction is preferred)."""
    s = np.linspace(0, size, n + 1)
    X, Y = np.meshgrid(s, s, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    idx = lambda i, j: i * (n + 1) + j  # noqa: E731
    tri = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tri += [[a, b, c], [a, c, d]] if (i + j) % 2 else [[a, b, d], [b, c, d]]
    return points, np.array(tri)


def write_fields(run_dir, points, triangles, phi):
    """A zero phi at t = 0, then phi at t = 2.5 (the last time, which the tool reads)."""
    write_vtk_run(run_dir, points[:, :2], triangles, {"phi": phi},
                  earlier=[(0.0, {"phi": np.zeros(len(points))})])


def test_a_linear_phi_gives_its_area_exactly_and_the_last_time(tmp_path):
    points, triangles = square_mesh(7)
    write_fields(tmp_path / "run", points, triangles, 0.7 - points[:, 0] + 0.1 * points[:, 1])
    b = budget(tmp_path / "run", -0.9)
    # {0.7 - x + 0.1 y > 0} in [0, 2]^2: x < 0.7 + 0.1 y, area 2 * 0.7 + 0.1 * 2 = 1.6
    assert abs(b["inside"] - 1.6) < 1e-12
    assert b["time"] == 2.5


def test_a_circle_converges_at_second_order(tmp_path):
    errors = []
    for n in (20, 40, 80):
        points, triangles = square_mesh(n)
        r = np.hypot(points[:, 0] - 1, points[:, 1] - 1)
        write_fields(tmp_path / f"n{n}", points, triangles, np.tanh((0.6 - r) / 0.05))
        errors.append(abs(budget(tmp_path / f"n{n}", -0.9)["inside"] - np.pi * 0.36))
    rates = [np.log2(a / b) for a, b in zip(errors, errors[1:])]
    print(f"circle area errors {errors}, rates {rates}")
    assert min(rates) > 1.5  # the zero line of a linear interpolant is O(h^2) off


def test_the_bulk_holds_its_shift_times_its_area(tmp_path):
    points, triangles = square_mesh(40)
    r = np.hypot(points[:, 0] - 1, points[:, 1] - 1)
    shift = 2e-4
    phi = np.where(r < 0.5, 1.0, -1.0 + shift)  # a disc and a bulk lifted by the shift
    write_fields(tmp_path / "run", points, triangles, phi)
    b = budget(tmp_path / "run", -0.9)
    # Every triangle with a vertex in the disc is not bulk; the rest holds shift / 2 each.
    assert abs(b["bulk"] - shift / 2 * b["bulk_area"]) < 1e-12
    assert 4 - np.pi * 0.6**2 < b["bulk_area"] < 4 - np.pi * 0.5**2
