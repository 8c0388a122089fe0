#!/usr/bin/python3
"""Plot the results of a cellphase run.

Writes PNG files into RUN_DIR/plots (or --out):
  observables.png  volume, membrane length/area, energies, circularity, centre of
                   mass and dofs over time (panels whose data are all zero are left out)
  timings.png      wall time of each step, stacked by part (assembly, solve, ...)
  cells.png        runs with several cells: each cell's volume change and centre path,
                   the largest overlap of two cells and the interaction energy
  level_sets.png   2D runs with fields (XDMF or VTK): the zero level set of phi at every
                   output time, coloured by time (level_sets_NAME.png for other fields)
"""
import argparse
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")  # files only: works without a display
import matplotlib.pyplot as plt
import numpy as np

from cellphase_results import (ResultsError, describe_fields, fields_index, read_fields,
                               read_observables, zero_level_set_2d)

PROG = "plot_run.py"


def relative_change(values):
    return values / values[0] - 1 if values[0] != 0 else values - values[0]


def plot_observables(obs, dim, title, path):
    size = {2: "area", 3: "volume"}.get(dim, "volume")
    membrane = {2: "length", 3: "area"}.get(dim, "length/area")
    # Each panel: title, y label, [(column, curve label, transform)].
    panels = [
        (f"cell {size}", "relative change", [("volume", None, relative_change)]),
        (f"membrane {membrane}", "relative change", [("surface", None, relative_change)]),
        ("energy", "energy", [("helfrich_energy", "Helfrich", None), ("total_energy", "total", None),
                              ("energy_ch", "Cahn-Hilliard", None)]),
        ("circularity", "circularity", [("circularity", None, None)]),
        ("centre of mass", "position", [("center_x", "x", None), ("center_y", "y", None),
                                        ("center_z", "z", None)]),
        ("degrees of freedom", "dofs", [("dofs", None, None)]),
        # flow runs only (the columns are zero otherwise, so the panels drop out)
        ("cell velocity", "velocity", [("cell_velocity_x", "x", None),
                                       ("rise_velocity", "y (rise)", None),
                                       ("cell_velocity_z", "z", None)]),
        ("energy with flow", "energy", [("kinetic_energy", "kinetic", None),
                                        ("total_energy_kinetic", "kinetic + interface", None)]),
        # polar gel runs only
        ("orientation energy (6.4)", "energy", [("polar_energy", None, None)]),
        ("mean orientation in the cell", "P", [("polar_P_cell_x", "x", None),
                                               ("polar_P_cell_y", "y", None)]),
    ]
    # Keep the curves whose column exists and is not all zero, and the panels left with one.
    panels = [(panel, ylabel, kept) for panel, ylabel, curves in panels
              if (kept := [c for c in curves if c[0] in obs and np.any(obs[c[0]] != 0)])]
    ncols = 3 if len(panels) > 4 else 2
    nrows = max(1, -(-len(panels) // ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.5 * ncols, 3.2 * nrows), squeeze=False,
                             constrained_layout=True)
    for ax, (panel, ylabel, curves) in zip(axes.flat, panels):
        for column, label, transform in curves:
            y = obs[column] if transform is None else transform(obs[column])
            ax.plot(obs["time"], y, label=label)
        ax.set(title=panel, xlabel="time", ylabel=ylabel)
        if len(curves) > 1:
            ax.legend()
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(f"{title}: observables")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def cell_names(obs):
    """The cells of a run with several phase fields (columns <cell>.volume), in order."""
    return [c[:-len(".volume")] for c in obs if c.endswith(".volume")]


def plot_cells(obs, title, path):
    cells = cell_names(obs)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    for cell in cells:
        axes[0].plot(obs["time"], relative_change(obs[f"{cell}.volume"]), label=cell)
        axes[1].plot(obs[f"{cell}.center_x"], obs[f"{cell}.center_y"], label=cell)
        axes[1].plot(obs[f"{cell}.center_x"][-1], obs[f"{cell}.center_y"][-1], "k.")
    axes[0].set(title="cell volume", xlabel="time", ylabel="relative change")
    axes[1].set(title="centre of each cell (dot: end)", xlabel="x", ylabel="y")
    axes[1].set_aspect("equal", adjustable="datalim")
    axes[2].plot(obs["time"], obs["overlap_max"], label="overlap max")
    if np.any(obs["interaction_energy"] != 0):
        axes[2].plot(obs["time"], obs["interaction_energy"], label="interaction energy (7.5)")
    axes[2].set(title="contact", xlabel="time")
    for ax in axes:
        if len(ax.get_lines()) > 1 and len(cells) <= 10:
            ax.legend(fontsize=8)
    fig.suptitle(f"{title}: {len(cells)} cells")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_timings(obs, title, path):
    parts = [c for c in obs if c.startswith("wall_") and np.any(obs[c] != 0)]
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    if parts:
        labels = [f"{c[5:]} ({obs[c].sum():.3g} s)" for c in parts]  # total per part in the legend
        # step="mid": each step is a flat band, not a ramp between neighbouring steps.
        ax.stackplot(obs["step"], *[obs[c] for c in parts], labels=labels, step="mid")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1))
    else:
        ax.text(0.5, 0.5, "no timings recorded", ha="center", transform=ax.transAxes)
    ax.set(title=f"{title}: wall time per step", xlabel="step", ylabel="seconds")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_level_sets(run_dir, field, title, path):
    """Zero level set of `field` (on a triangle mesh) at every output time."""
    times, curves, bounds = [], [], []
    for time, points, cells, values in read_fields(run_dir, fields=[field]):
        times.append(time)
        curves.append(zero_level_set_2d(points[:, :2], cells, values[field]))
        bounds.append((points[:, :2].min(axis=0), points[:, :2].max(axis=0)))
    if not times:
        raise ResultsError(f"{fields_index(run_dir)}: field {field} has no output times")
    fig, ax = plt.subplots(figsize=(6.5, 5.5), constrained_layout=True)
    # Guard a single output time: a zero-width colour range cannot be drawn.
    norm = plt.Normalize(min(times), max(times) if max(times) > min(times) else min(times) + 1)
    cmap = plt.get_cmap("viridis")
    for time, pieces in zip(times, curves):
        for piece in pieces:
            ax.plot(piece[:, 0], piece[:, 1], color=cmap(norm(time)), lw=1.2)
    lower = np.min([b[0] for b in bounds], axis=0)
    upper = np.max([b[1] for b in bounds], axis=0)
    ax.set(xlim=(lower[0], upper[0]), ylim=(lower[1], upper[1]), xlabel="x", ylabel="y",
           title=f"{title}: zero level set of {field}")
    ax.set_aspect("equal")
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="time")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROG, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", metavar="RUN_DIR", type=Path,
                        help="output directory of a run (holds observables.csv, fields.xdmf or fields.pvd)")
    parser.add_argument("--out", metavar="DIR", type=Path,
                        help="where to write the plots (default: RUN_DIR/plots)")
    parser.add_argument("--fields", metavar="NAME", nargs="+", default=["phi"],
                        help="fields whose zero level set is drawn (default: phi)")
    args = parser.parse_args(argv)

    def fail(message):
        print(f"{PROG}: error: {message}", file=sys.stderr)
        return 1

    run_dir = args.run_dir
    if not run_dir.is_dir():
        return fail(f"{run_dir}: no such directory")
    try:
        obs = read_observables(run_dir)
        # Reads the index only (not the data): field names, and 2D or 3D for the labels.
        index = fields_index(run_dir)
        has_fields = index is not None
        names, dim = describe_fields(run_dir) if has_fields else ([], None)
    except ResultsError as e:
        return fail(e)
    if len(obs["time"]) == 0:
        return fail(f"{run_dir / 'observables.csv'}: no complete rows")
    # With several cells, "phi" stands for every phi_<cell>.
    fields = [g for f in args.fields
              for g in ([f] if f in names or not has_fields
                        else [n for n in names if n.startswith(f + "_")] or [f])]
    missing = [f for f in fields if f not in names]
    if has_fields and missing:
        return fail(f"no field {', '.join(missing)} in {index} "
                    f"(it has: {', '.join(names) or 'none'})")

    out = args.out or run_dir / "plots"
    out.mkdir(parents=True, exist_ok=True)
    title = run_dir.resolve().name
    plot_observables(obs, dim, title, out / "observables.png")
    plot_timings(obs, title, out / "timings.png")
    print(out / "observables.png")
    print(out / "timings.png")
    if cell_names(obs) and "overlap_max" in obs:
        plot_cells(obs, title, out / "cells.png")
        print(out / "cells.png")

    if not has_fields:
        print(f"note: {run_dir / 'fields.xdmf'} not found (nor fields.pvd): plotted the observables only")
    elif dim != 2:
        print("note: level sets are plotted for 2D runs only")
    else:
        for field in fields:
            path = out / ("level_sets.png" if field == "phi" else f"level_sets_{field}.png")
            try:
                plot_level_sets(run_dir, field, title, path)
            except ResultsError as e:
                return fail(e)
            print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
