"""Figures of a GTPase motile-cell run (thesis Fig. 5.3 and 5.4).

Usage: /usr/bin/python3 demos/gtpase-motile-cell/plot_cell.py [RUN_DIR] [--times T ...]

RUN_DIR (default output/gtpase-motile-cell) holds observables.csv and fields.xdmf. Writes
into RUN_DIR:
  fig-5-4.png      one column per time: the zero level set over c1 (on the membrane band
                   |phi| < 0.9), c2 (the same) and C (in the cell, phi > 0), and |v| with
                   its direction, as the rows of Fig. 5.4 (--phi-row adds phi first, as in
                   Fig. 5.7; --figure names the file); the view fits the cell;
  observables.png  x_cm (5.19), v_cm, circularity (5.20), Helfrich energy, the cell's volume
                   and the GTPase amount (Fig. 5.3) against time.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))
import cellphase_results  # noqa: E402


def nearest_frames(run_dir, times):
    """The output frames closest to the wanted times."""
    frames = list(cellphase_results.read_fields(run_dir, ["phi", "c1", "c2", "C", "v"]))
    if not frames:
        sys.exit(f"{run_dir}: no field output (output.fields and output.every)")
    picked = []
    for t in times:
        picked.append(min(frames, key=lambda f: abs(f[0] - t)))
    return picked


def colour_range(values):
    """vmin, vmax of the values shown (a constant field gets a range around its value)."""
    lo, hi = float(np.min(values)), float(np.max(values))
    if hi - lo <= 1e-9 * max(1.0, abs(hi)):
        lo, hi = lo - 0.5, hi + 0.5
    return {"vmin": lo, "vmax": hi}


def view_box(frames):
    """Half-widths of the view about the cell's centre: the band phi > -0.9 of every frame
    drawn, with a margin, and at least 1.8 x 1.5 (a cell of radius 1)."""
    hx, hy = 1.8, 1.5
    for _, points, _, values in frames:
        phi = values["phi"]
        centre = points[phi > 0].mean(axis=0)
        band = points[phi > -0.9]
        hx = max(hx, float(np.max(np.abs(band[:, 0] - centre[0]))) + 0.3)
        hy = max(hy, float(np.max(np.abs(band[:, 1] - centre[1]))) + 0.3)
    return hx, hy


def draw_fields(run_dir, times, figure, phi_row):
    frames = nearest_frames(run_dir, times)
    rows = [("c1", "membrane"), ("c2", "membrane"), ("C", "bulk"), ("|v|", None)]
    if phi_row:
        rows.insert(0, ("phi", "everywhere"))
    hx, hy = view_box(frames)
    fig, axes = plt.subplots(len(rows), len(frames), figsize=(2.6 * len(frames), 2.1 * len(rows)),
                             squeeze=False, constrained_layout=True)
    for j, (time, points, cells, values) in enumerate(frames):
        tri = mtri.Triangulation(points[:, 0], points[:, 1], cells)
        phi = values["phi"]
        centre = points[phi > 0].mean(axis=0)
        for i, (name, where) in enumerate(rows):
            ax = axes[i][j]
            if name == "|v|":
                v = values["v"][:, :2]
                speed = np.linalg.norm(v, axis=1)
                image = ax.tripcolor(tri, speed, shading="gouraud", cmap="viridis",
                                     **colour_range(speed))
                # Directions on a coarse grid of the view
                gx, gy = np.meshgrid(np.linspace(centre[0] - hx + 0.2, centre[0] + hx - 0.2, 13),
                                     np.linspace(centre[1] - hy + 0.2, centre[1] + hy - 0.2, 11))
                vx = mtri.LinearTriInterpolator(tri, v[:, 0])(gx, gy)
                vy = mtri.LinearTriInterpolator(tri, v[:, 1])(gx, gy)
                ax.quiver(gx, gy, vx, vy, color="w", width=0.005)
            else:
                data = np.array(values[name], dtype=float)
                outside = {"membrane": np.abs(phi) >= 0.9, "bulk": phi <= 0,
                           "everywhere": np.zeros(phi.shape, dtype=bool)}[where]
                hidden = np.all(outside[cells], axis=1)  # triangles entirely outside the region
                shown = mtri.Triangulation(points[:, 0], points[:, 1], cells, mask=hidden)
                image = ax.tripcolor(shown, data, shading="gouraud", cmap="magma",
                                     **colour_range(data[~outside]))
            ax.tricontour(tri, phi, levels=[0.0], colors="k", linewidths=0.8)
            ax.set_xlim(centre[0] - hx, centre[0] + hx)
            ax.set_ylim(centre[1] - hy, centre[1] + hy)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            fig.colorbar(image, ax=ax, shrink=0.7)
            if i == 0:
                ax.set_title(f"t = {time:g}")
            if j == 0:
                ax.set_ylabel(name)
    path = run_dir / figure
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def draw_observables(run_dir):
    o = cellphase_results.read_observables(run_dir)
    t = np.array(o["time"])
    panels = [("center_x", "x_cm (5.19)"), ("cell_velocity_x", "v_cm"),
              ("circularity", "circularity (5.20)"), ("helfrich_energy", "Helfrich energy"),
              ("volume", "cell volume"), ("rd_mass", "GTPase amount")]
    fig, axes = plt.subplots(2, 3, figsize=(11, 5.5), constrained_layout=True)
    for ax, (key, label) in zip(axes.flat, panels):
        y = np.array(o[key])
        if key in ("volume", "rd_mass"):
            ax.plot(t, (y - y[0]) / y[0])
            ax.set_ylabel(f"{label}: relative change")
        else:
            ax.plot(t, y)
            ax.set_ylabel(label)
        ax.set_xlabel("t")
        ax.grid(alpha=0.3)
    path = run_dir / "observables.png"
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", nargs="?", default="output/gtpase-motile-cell", type=pathlib.Path)
    parser.add_argument("--times", nargs="+", type=float, default=[0.0, 0.3, 0.6, 1.2, 3.5],
                        help="times of the columns (the nearest output frame is drawn; "
                             "Fig. 5.4 shows 0.013, 0.3, 0.6, 1.2 and 8)")
    parser.add_argument("--figure", default="fig-5-4.png",
                        help="file name of the field figure in RUN_DIR (default fig-5-4.png)")
    parser.add_argument("--phi-row", action="store_true",
                        help="a first row with the phase field (as Fig. 5.7)")
    args = parser.parse_args()
    if not (args.run_dir / "observables.csv").exists():
        sys.exit(f"{args.run_dir}: no observables.csv (run the scene first)")
    draw_observables(args.run_dir)
    draw_fields(args.run_dir, args.times, args.figure, args.phi_row)


if __name__ == "__main__":
    main()
