"""Figures of an active polar gel run (thesis Figs. 6.5-6.7 and 6.15).

Usage: /usr/bin/python3 python/plot_polar_gel.py RUN_DIR [--times T ...] [--half-width W]

RUN_DIR holds observables.csv and fields.xdmf with the fields phi, P and v. Writes into
RUN_DIR:
  polar-gel.png     one column per time, three rows as in Fig. 6.5: |P| with the direction
                    of P and the zero level set; the velocity in the laboratory frame; the
                    velocity in the co-moving frame, v minus the cell's mean velocity at that
                    time ((v1 - v_cell, v2) of section 6.4.3 for a cell moving along x);
  polar-motion.png  the observables of plot_run.py against time: volume, energies,
                    circularity (5.20), centre, mean velocity, the orientation energy (6.4)
                    and the mean orientation in the cell.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import cellphase_results  # noqa: E402
import plot_run  # noqa: E402


def nearest_frames(run_dir, times):
    needed = {"phi", "P", "v"}
    frames = [f for f in cellphase_results.read_fields(run_dir, sorted(needed))
              if needed <= set(f[3])]
    if not frames:
        sys.exit(f"{run_dir}: no field output with phi, P and v (output.fields, output.every)")
    return [min(frames, key=lambda f: abs(f[0] - t)) for t in times]


def arrows(ax, tri, field, centre, half_width, colour):
    """Directions of a vector field on a 15 x 11 grid of the view."""
    gx, gy = np.meshgrid(np.linspace(centre[0] - half_width, centre[0] + half_width, 15),
                         np.linspace(centre[1] - 0.75 * half_width, centre[1] + 0.75 * half_width, 11))
    fx = mtri.LinearTriInterpolator(tri, field[:, 0])(gx, gy)
    fy = mtri.LinearTriInterpolator(tri, field[:, 1])(gx, gy)
    ax.quiver(gx, gy, fx, fy, color=colour, width=0.004)


def draw_panel(fig, ax, tri, phi, field, centre, half_width):
    """|field| with its direction and the zero level set of phi, around centre."""
    size = np.linalg.norm(field, axis=1)
    image = ax.tripcolor(tri, size, shading="gouraud", cmap="viridis")
    if size.max() > 0:  # (the velocity before the first step is zero)
        arrows(ax, tri, field, centre, half_width, "w")
    ax.tricontour(tri, phi, levels=[0.0], colors="r", linewidths=0.8)
    ax.set_xlim(centre[0] - 1.1 * half_width, centre[0] + 1.1 * half_width)
    ax.set_ylim(centre[1] - 0.85 * half_width, centre[1] + 0.85 * half_width)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    fig.colorbar(image, ax=ax, shrink=0.7)


def draw_fields(run_dir, obs, times, half_width):
    frames = nearest_frames(run_dir, times)
    rows = ["|P|", "|v| (laboratory)", "|v| (co-moving)"]
    fig, axes = plt.subplots(len(rows), len(frames), figsize=(3.2 * len(frames), 2.5 * len(rows)),
                             squeeze=False, constrained_layout=True)
    for j, (time, points, cells, values) in enumerate(frames):
        tri = mtri.Triangulation(points[:, 0], points[:, 1], cells)
        phi = values["phi"]
        inside = np.clip((1 + phi) / 2, 0, 1)
        centre = (points[:, :2] * inside[:, None]).sum(axis=0) / inside.sum()
        if half_width is None:  # the cell and a margin of half its size
            extent = np.abs(points[phi > 0, :2] - centre).max(axis=0)
            half_width = 1.5 * max(extent[0], extent[1] / 0.75)
        k = int(np.argmin(np.abs(np.asarray(obs["time"]) - time)))
        v_cell = float(obs["cell_velocity_x"][k])
        v_cell_y = float(obs["cell_velocity_y"][k]) if "cell_velocity_y" in obs else 0.0
        P = values["P"][:, :2]
        v = values["v"][:, :2]
        co_moving = v - np.array([v_cell, v_cell_y])
        for i, (name, field) in enumerate(zip(rows, [P, v, co_moving])):
            ax = axes[i][j]
            draw_panel(fig, ax, tri, phi, field, centre, half_width)
            if i == 0:
                ax.set_title(f"t = {time:g}, v_cell = ({v_cell:.3g}, {v_cell_y:.3g})", fontsize=9)
            if j == 0:
                ax.set_ylabel(name)
    path = run_dir / "polar-gel.png"
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", type=pathlib.Path)
    parser.add_argument("--times", nargs="+", type=float,
                        help="times of the columns, the nearest output frame each "
                             "(default: four frames spread over the run)")
    parser.add_argument("--half-width", type=float,
                        help="half the width of the view around the cell (default: 1.5 times "
                             "the cell's half-extent in the first frame drawn)")
    args = parser.parse_args()
    if not (args.run_dir / "observables.csv").exists():
        sys.exit(f"{args.run_dir}: no observables.csv (run the scene first)")
    # The motion against time: the observables panels of plot_run.py (those of the gel
    # included), under the name the demos use.
    obs = cellphase_results.read_observables(args.run_dir)
    plot_run.plot_observables(obs, 2, args.run_dir.name, args.run_dir / "polar-motion.png")
    times = args.times
    if not times:
        end = float(obs["time"][-1])
        times = [end * f for f in (0.0, 1 / 3, 2 / 3, 1.0)]
    draw_fields(args.run_dir, obs, times, args.half_width)


if __name__ == "__main__":
    main()
