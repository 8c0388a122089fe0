#!/usr/bin/python3
"""Compare an active polar gel cell with a squirmer (thesis section 6.5).

Fits, on the last (or a chosen) output frame of a 2D run,
  * the tangential surface velocity on phi = 0 to the squirmer profile (eq. 6.18)
        v_T(alpha) = n1 (sin(alpha) + m sin(2 alpha)),
    m > 0 puller, m < 0 pusher, m = 0 neutral;
  * the velocity outside the circle |x - x_cm| > R (default 5) to the far field (eq. 6.19)
    with a uniform part, a Stokeslet, a stresslet and a source dipole.
Both fits are in the frame moving with the cell: x - x_cm, v - v_cell e1, the cell
swimming along +x (the squirmer axis).

Sign convention (checked by tests/python/test_squirmer_fit.py): v_T is the co-moving
velocity along the counter-clockwise tangent e_alpha = (-sin alpha, cos alpha). A cell
swimming in +x whose surface flow goes from front to rear (fluid moving backwards past the
body) has n1 > 0. Blake's u_theta = B1 sin(theta) + B2 sin(theta) cos(theta) along
e_theta (theta from the swimming direction, e_theta pointing from front to rear) gives
n1 = B1 and m = B2 / (2 B1): a puller (B2 > 0) has m > 0.

Prints n1, m, the measured v_cell, the far-field coefficients (v_cell_fit, A_st, A_str,
A_sd) and the frame's time, one `name = value` per line.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

from cellphase_results import ResultsError, read_fields, zero_level_set_2d

PROG = "squirmer_fit.py"
FAR_FIELD_NAMES = ("v_cell", "A_st", "A_str", "A_sd")


# --- surface profile, eq. (6.18) ---------------------------------------------------------

def squirmer_profile(alpha, n1, m):
    """v_T(alpha) = n1 (sin alpha + m sin 2 alpha), eq. (6.18)."""
    alpha = np.asarray(alpha, dtype=float)
    return n1 * (np.sin(alpha) + m * np.sin(2 * alpha))


def fit_squirmer_profile(alpha, vT):
    """(n1, m) of eq. (6.18) by linear least squares on vT = A sin a + B sin 2a."""
    alpha = np.asarray(alpha, dtype=float).ravel()
    vT = np.asarray(vT, dtype=float).ravel()
    if alpha.shape != vT.shape:
        raise ValueError(f"squirmer fit: {alpha.size} angles but {vT.size} velocities")
    if alpha.size < 3:
        raise ValueError(f"squirmer fit: needs at least 3 samples, got {alpha.size}")
    design = np.column_stack([np.sin(alpha), np.sin(2 * alpha)])
    (A, B), *_ = np.linalg.lstsq(design, vT, rcond=None)
    if A == 0:
        raise ValueError("squirmer fit: the sin(alpha) coefficient n1 is 0, so m = B/n1 "
                         "is undefined")
    return float(A), float(B / A)


# --- far field, eq. (6.19) ---------------------------------------------------------------

def _far_field_modes(points):
    """The four N x 2 velocity fields multiplying v_cell, A_st, A_str, A_sd in eq. (6.19)."""
    x = np.asarray(points, dtype=float)[:, :2]
    r = np.linalg.norm(x, axis=1)[:, None]
    rhat = x / r
    c = rhat[:, :1]                                   # x1 / r = rhat . e1
    e1 = np.array([1.0, 0.0])
    uniform = -np.broadcast_to(e1, x.shape)
    stokeslet = -(e1 + rhat * c) / r                  # -(I + rhat rhat^T) e1 / r
    stresslet = -(1 - 3 * c**2) * rhat / r**2
    dipole = -(e1 / 3 - rhat * c) / r**3              # -(I/3 - rhat rhat^T) e1 / r^3
    return [uniform, stokeslet, stresslet, dipole]


def far_field(points, v_cell, A_st, A_str, A_sd):
    """Velocity (N x 2) of eq. (6.19) at points (N x 2, cell centre at the origin)."""
    modes = _far_field_modes(points)
    return sum(c * f for c, f in zip((v_cell, A_st, A_str, A_sd), modes))


def fit_far_field(points, velocities, radius=5.0):
    """{v_cell, A_st, A_str, A_sd} of eq. (6.19) by linear least squares on both velocity
    components at the points with |x| > radius (the thesis fits outside R = 5)."""
    points = np.asarray(points, dtype=float)[:, :2]
    velocities = np.asarray(velocities, dtype=float)[:, :2]
    outside = np.linalg.norm(points, axis=1) > radius
    if outside.sum() < 4:
        raise ValueError(f"far-field fit: {outside.sum()} points outside r = {radius}, "
                         "needs at least 4")
    modes = _far_field_modes(points[outside])
    design = np.column_stack([f.ravel() for f in modes])  # rows: (u1, u2) of each point
    # The modes decay like 1, 1/r, 1/r^2, 1/r^3: scale the columns to keep lstsq well posed.
    scale = np.linalg.norm(design, axis=0)
    coeffs, *_ = np.linalg.lstsq(design / scale, velocities[outside].ravel(), rcond=None)
    return dict(zip(FAR_FIELD_NAMES, (coeffs / scale).tolist()))


# --- sampling a simulation ---------------------------------------------------------------

def tangential_profile(points, cells, phi, v, centre, v_cell):
    """(alpha, vT) on the zero level set of phi, sorted by alpha in [0, 2 pi).

    The samples are the midpoints of the segments of the longest piece of the P1 contour
    (each midpoint lies inside one triangle, and the segment gives the tangent); v is
    interpolated linearly there, v_cell is subtracted from its x component (co-moving
    frame) and vT is its component along the contour tangent oriented like
    e_alpha = (-sin alpha, cos alpha), alpha = atan2(y - cy, x - cx). With this
    orientation a cell swimming in +x with front-to-rear surface flow has n1 > 0 in
    fit_squirmer_profile(alpha, vT).
    """
    import matplotlib.tri as mtri

    points = np.asarray(points, dtype=float)[:, :2]
    v = np.asarray(v, dtype=float)[:, :2]
    curves = zero_level_set_2d(points, cells, phi)
    if not curves:
        raise ValueError("tangential profile: phi has no zero level set")
    # Other pieces (a second cell, a sliver at the boundary) would mix in other surfaces.
    curve = max(curves, key=lambda c: np.linalg.norm(np.diff(c, axis=0), axis=1).sum())
    chord = np.diff(curve, axis=0)
    keep = np.linalg.norm(chord, axis=1) > 0         # a contour through a node repeats it
    mid = 0.5 * (curve[1:] + curve[:-1])[keep]
    tangent = chord[keep] / np.linalg.norm(chord[keep], axis=1)[:, None]

    rel = mid - np.asarray(centre, dtype=float)[:2]
    alpha = np.mod(np.arctan2(rel[:, 1], rel[:, 0]), 2 * np.pi)
    e_alpha = np.column_stack([-np.sin(alpha), np.cos(alpha)])
    tangent *= np.where(np.sum(tangent * e_alpha, axis=1) < 0, -1.0, 1.0)[:, None]

    triangulation = mtri.Triangulation(points[:, 0], points[:, 1], cells)
    u = np.column_stack([mtri.LinearTriInterpolator(triangulation, v[:, k])(mid[:, 0], mid[:, 1])
                         .filled(np.nan) for k in range(2)])
    u[:, 0] -= v_cell
    vT = np.sum(u * tangent, axis=1)
    ok = np.isfinite(vT)
    order = np.argsort(alpha[ok])
    return alpha[ok][order], vT[ok][order]


def far_field_samples(points, phi, v, centre, v_cell, radius):
    """(x - centre, v - v_cell e1) at the nodes outside the cell (phi < 0) with
    |x - centre| > radius, ready for fit_far_field."""
    x = np.asarray(points, dtype=float)[:, :2] - np.asarray(centre, dtype=float)[:2]
    u = np.array(v, dtype=float)[:, :2]
    u[:, 0] -= v_cell
    keep = (np.linalg.norm(x, axis=1) > radius) & (np.asarray(phi) < 0)
    return x[keep], u[keep]


def cell_centre_and_velocity(points, cells, phi, v):
    """Centre and mean x velocity of the cell, weighted by phi~ = (1 + phi)/2 clipped to
    [0, 1] times the lumped (nodal) area, a third of each adjacent triangle's area:
    plain node counts would favour the refined mesh at the interface."""
    points = np.asarray(points, dtype=float)[:, :2]
    a, b, c = (points[np.asarray(cells)[:, k]] for k in range(3))
    area = 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    lumped = np.zeros(len(points))
    for k in range(3):
        np.add.at(lumped, np.asarray(cells)[:, k], area / 3)
    w = np.clip((1 + np.asarray(phi, dtype=float)) / 2, 0, 1) * lumped
    if w.sum() <= 0:
        raise ValueError("cell centre: phi~ = (1 + phi)/2 vanishes everywhere (no cell)")
    centre = w @ points / w.sum()
    v_cell = w @ np.asarray(v, dtype=float)[:, 0] / w.sum()
    return centre, float(v_cell)


# --- plots -------------------------------------------------------------------------------

def _save(fig, path):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    FigureCanvasAgg(fig)                               # Agg canvas: no pyplot, no display
    fig.savefig(path, dpi=150)


def plot_profile(alpha, vT, n1, m, path):
    """PNG of the sampled v_T (markers) and the fitted eq. (6.18) (line) against alpha."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(np.degrees(alpha), vT, ".", ms=3, label="simulation")
    a = np.linspace(0, 2 * np.pi, 361)
    ax.plot(np.degrees(a), squirmer_profile(a, n1, m), "-",
            label=f"squirmer fit: $n_1$ = {n1:.4g}, m = {m:.4g}")
    ax.set_xlabel(r"$\alpha$ (degrees)")
    ax.set_ylabel(r"$v_T$")
    ax.set_xlim(0, 360)
    ax.legend()
    _save(fig, path)


def plot_far_field(points, velocities, coeffs, path, radius=5.0, arrows=600):
    """PNG of the sampled co-moving velocity (black) and the fitted eq. (6.19) (red)."""
    from matplotlib.figure import Figure
    points = np.asarray(points, dtype=float)[:, :2]
    velocities = np.asarray(velocities, dtype=float)[:, :2]
    step = max(1, len(points) // arrows)               # thin out: unreadable otherwise
    p, u = points[::step], velocities[::step]
    fit = far_field(p, *(coeffs[k] for k in FAR_FIELD_NAMES))
    fig = Figure(figsize=(8, 4.5), layout="constrained")
    ax = fig.add_subplot()
    scale = np.abs(u).max() * 30 if len(u) else None
    ax.quiver(p[:, 0], p[:, 1], u[:, 0], u[:, 1], color="k", scale=scale, label="simulation")
    ax.quiver(p[:, 0], p[:, 1], fit[:, 0], fit[:, 1], color="r", scale=scale, alpha=0.6,
              label="far-field fit")
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(radius * np.cos(t), radius * np.sin(t), "b--", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("$x_1$ (from the cell centre)")
    ax.set_ylabel("$x_2$ (from the cell centre)")
    ax.legend(loc="upper right")
    _save(fig, path)


# --- command line ------------------------------------------------------------------------

def _frame(run_dir, time, phi_name, v_name):
    frames = list(read_fields(run_dir, fields=[phi_name, v_name]))
    if not frames:
        raise ResultsError(f"{run_dir}: the run has no output frames")
    if time is None:
        frame = frames[-1]
    else:
        frame = min(frames, key=lambda f: abs(f[0] - time))
    t, points, cells, values = frame
    for name in (phi_name, v_name):
        if name not in values:
            raise ResultsError(f"{run_dir}: no field {name!r} at time {t:g} "
                               f"(fields read: {sorted(values)})")
    if cells.shape[1] != 3:
        raise ResultsError(f"{run_dir}: not a 2D triangle mesh (cells with {cells.shape[1]} "
                           "nodes); the squirmer fit is for 2D runs")
    return t, points[:, :2], cells, values[phi_name], values[v_name]


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROG, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", metavar="RUN_DIR", help="output directory of a 2D run")
    parser.add_argument("--time", type=float, help="use the output frame nearest to this "
                        "time (default: the last one)")
    parser.add_argument("--radius", type=float, default=5.0,
                        help="fit the far field outside this distance from the cell centre "
                        "(default 5, as in the thesis)")
    parser.add_argument("--plot", metavar="PNG", help="write v_T(alpha) and its fit here")
    parser.add_argument("--plot-far-field", metavar="PNG",
                        help="write the far-field samples and their fit here")
    parser.add_argument("--phi", default="phi", help="name of the phase field (default phi)")
    parser.add_argument("--velocity", default="v", help="name of the velocity field "
                        "(default v)")
    args = parser.parse_args(argv)

    run_dir = Path(args.run_dir)
    try:
        if not run_dir.is_dir():
            raise ResultsError(f"{run_dir}: no such directory")
        t, points, cells, phi, v = _frame(run_dir, args.time, args.phi, args.velocity)
        centre, v_cell = cell_centre_and_velocity(points, cells, phi, v)
        alpha, vT = tangential_profile(points, cells, phi, v, centre, v_cell)
        n1, m = fit_squirmer_profile(alpha, vT)
        x, u = far_field_samples(points, phi, v, centre, v_cell, args.radius)
        coeffs = fit_far_field(x, u, args.radius)
        if args.plot:
            plot_profile(alpha, vT, n1, m, args.plot)
        if args.plot_far_field:
            plot_far_field(x, u, coeffs, args.plot_far_field, args.radius)
    except (ResultsError, ValueError, OSError) as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    results = {"time": t, "n1": n1, "m": m, "v_cell": v_cell,
               "v_cell_fit": coeffs["v_cell"], "A_st": coeffs["A_st"],
               "A_str": coeffs["A_str"], "A_sd": coeffs["A_sd"]}
    for name, value in results.items():
        print(f"{name} = {value:.6g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
