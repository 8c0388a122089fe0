"""Figures of a chemotaxis run (thesis section 5.4.3, Figs. 5.8-5.11).

Usage: /usr/bin/python3 demos/gtpase-chemotaxis/plot_chemotaxis.py SCENE [--run RUN_DIR]
           [--times T ...]

SCENE is the run's scene file: its chemotaxis mode and output directory are read from it
(--run names another directory). Writes into the run's directory:
  track.png      the cell's zero level set at the chosen times (light to dark) in the
                 domain, the path of the centre x_cm (5.19) from S (start) to E (end), and
                 at each drawn time an arrow along the signal grad c~ at the centre;
  polarity.png   the angle of the c1 maximum (the cell's front) and of the signal against
                 time, the speed |v_cm| and the circularity (5.20).
It prints a table of the centre, speed, circularity, front and signal at the drawn times,
and the largest relative change of the cell's volume and of the GTPase amount.
The signal's angle is the observable rd_signal_angle_deg; for runs without it, it is
computed from the scene for the uniform modes 1 and 2.
"""
import argparse
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))
import cellphase_results  # noqa: E402


def signal_angles(observables, chemotaxis):
    """Degrees of grad c~ at the output rows: logged, or (modes 1, 2) from the scene."""
    if "rd_signal_angle_deg" in observables:
        return np.array(observables["rd_signal_angle_deg"])
    t = np.array(observables["time"])
    mode, omega = chemotaxis.get("mode"), chemotaxis.get("omega")
    if mode == "rotating":
        return np.degrees(omega * t)
    if mode == "sinusoidal":
        return np.degrees(np.arctan(np.sin(omega * t)))
    sys.exit(f"observables.csv has no rd_signal_angle_deg and mode {mode!r} is not uniform: "
             "rerun the scene to log the signal's direction")


def boundary_segments(points, cells):
    """The domain's outline: the edges of exactly one triangle."""
    edges = np.sort(np.concatenate([cells[:, [0, 1]], cells[:, [1, 2]], cells[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    return points[unique[counts == 1]][:, :, :2]


def frames_at(run_dir, times):
    """The phi output frames nearest to the wanted times (each frame once, in time order)."""
    wanted = sorted(set(times))
    frames = {}
    for frame in cellphase_results.read_fields(run_dir, ["phi"]):
        for t in wanted:
            best = frames.get(t)
            if best is None or abs(frame[0] - t) < abs(best[0] - t):
                frames[t] = frame
    if not frames:
        sys.exit(f"{run_dir}: no phi in the field output (output.fields)")
    unique = {f[0]: f for f in frames.values()}
    return [unique[t] for t in sorted(unique)]


def save(fig, path, dpi):
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    print(f"wrote {path}")


def draw_track(run_dir, observables, angles, times, title):
    frames = frames_at(run_dir, times)
    t_obs = np.array(observables["time"])
    cx, cy = np.array(observables["center_x"]), np.array(observables["center_y"])
    fig, ax = plt.subplots(figsize=(7.5, 6), constrained_layout=True)
    outline = boundary_segments(frames[0][1], frames[0][2])
    for seg in outline:
        ax.plot(seg[:, 0], seg[:, 1], color="0.3", lw=1.2)
    colours = plt.cm.viridis(np.linspace(0.15, 0.95, len(frames)))
    for colour, (time, points, cells, values) in zip(colours, frames):
        for k, curve in enumerate(cellphase_results.zero_level_set_2d(points, cells, values["phi"])):
            ax.plot(curve[:, 0], curve[:, 1], color=colour, lw=1.4,
                    label=f"t = {time:.3g}" if k == 0 else None)
        row = int(np.argmin(np.abs(t_obs - time)))
        a = math.radians(angles[row])
        ax.annotate("", xy=(cx[row] + 0.8 * math.cos(a), cy[row] + 0.8 * math.sin(a)),
                    xytext=(cx[row], cy[row]),
                    arrowprops={"arrowstyle": "->", "color": colour, "lw": 1.5})
    ax.plot(cx, cy, color="crimson", lw=1, ls="--", label="x_cm")
    ax.text(cx[0], cy[0], " S", color="crimson", fontsize=12, va="center")
    ax.text(cx[-1], cy[-1], " E", color="crimson", fontsize=12, va="center")
    ax.set_aspect("equal")
    ax.set_title(title + "\n(arrows: the signal grad c~ at the drawn times)", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    save(fig, run_dir / "track.png", dpi=120)


def draw_polarity(run_dir, observables, angles):
    t = np.array(observables["time"])
    front = np.degrees(np.unwrap(np.radians(observables["rd_c1_max_angle_deg"])))
    signal = np.degrees(np.unwrap(np.radians(angles)))
    # Start both on the same turn, so the curves can be compared
    front += 360 * round((signal[0] - front[0]) / 360)
    speed = np.hypot(observables["cell_velocity_x"], observables["cell_velocity_y"])
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), constrained_layout=True)
    axes[0].plot(t, signal, label="signal grad c~")
    axes[0].plot(t, front, label="c1 maximum (front)", lw=1)
    axes[0].set_ylabel("angle [degrees]")
    axes[0].legend(fontsize=8)
    axes[1].plot(t, speed)
    axes[1].set_ylabel("|v_cm|")
    axes[2].plot(t, observables["circularity"])
    axes[2].set_ylabel("circularity (5.20)")
    for ax in axes:
        ax.set_xlabel("t")
        ax.grid(alpha=0.3)
    save(fig, run_dir / "polarity.png", dpi=110)


def print_summary(observables, angles, times):
    t = np.array(observables["time"])
    print("| t | x_cm | y_cm | \\|v_cm\\| | circularity | front (c1 max) deg | signal deg |")
    print("|---|---|---|---|---|---|---|")
    for wanted in times:
        i = int(np.argmin(np.abs(t - wanted)))
        speed = math.hypot(observables["cell_velocity_x"][i], observables["cell_velocity_y"][i])
        print(f"| {t[i]:g} | {observables['center_x'][i]:.2f} | {observables['center_y'][i]:.2f} "
              f"| {speed:.2f} | {observables['circularity'][i]:.3f} "
              f"| {observables['rd_c1_max_angle_deg'][i]:.0f} | {angles[i]:.0f} |")
    for key, label in [("volume", "cell volume"), ("rd_mass", "GTPase amount")]:
        y = np.array(observables[key])
        print(f"{label}: largest relative change {np.max(np.abs(y - y[0])) / abs(y[0]):.1e}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", type=pathlib.Path, help="the run's scene file")
    parser.add_argument("--run", type=pathlib.Path,
                        help="the run's output directory (default: the scene's output.directory)")
    parser.add_argument("--times", nargs="+", type=float,
                        help="times of the drawn shapes (default: 7 from start to end)")
    args = parser.parse_args()
    try:
        scene = yaml.safe_load(args.scene.read_text())
    except (OSError, yaml.YAMLError) as error:
        sys.exit(f"{args.scene}: {error}")
    chemotaxis = (scene.get("reaction_diffusion") or {}).get("chemotaxis")
    if not chemotaxis:
        sys.exit(f"{args.scene}: no reaction_diffusion.chemotaxis")
    run_dir = args.run or pathlib.Path(scene.get("output", {}).get("directory", ""))
    if not (run_dir / "observables.csv").exists():
        sys.exit(f"{run_dir}: no observables.csv (run the scene first)")
    observables = cellphase_results.read_observables(run_dir)
    angles = signal_angles(observables, chemotaxis)
    end = observables["time"][-1]
    times = args.times or list(np.linspace(0, end, 7))
    title = f"{args.scene.name}: chemotaxis mode {chemotaxis['mode']}, xi {chemotaxis.get('xi', 5)}"
    draw_track(run_dir, observables, angles, times, title)
    draw_polarity(run_dir, observables, angles)
    print_summary(observables, angles, times)


if __name__ == "__main__":
    main()
