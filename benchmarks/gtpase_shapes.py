#!/usr/bin/python3
"""Stationary shape and speed of the motile GTPase cell against one mechanical parameter
(thesis Figs. 5.5 and 5.6, section 5.4.1), from a sweep of the study tool:

  benchmarks/studies/gtpase-protrusion.yaml   alpha (Fa), Fig. 5.5c and Fig. 5.6
  benchmarks/studies/gtpase-tension.yaml      sigma (Ca), Fig. 5.5b
  benchmarks/studies/gtpase-bending.yaml      b_N (Be, with gamma = 0.01 Be), Fig. 5.5a

Usage: /usr/bin/python3 benchmarks/gtpase_shapes.py STUDY.yaml [--run] [--jobs N]
                                                     [--with KEY=VALUE:RUN_DIR ...]

With --run the members not yet done are run first (python/study.py run). --with adds a
finished member of another study that is the same scene as this sweep at KEY=VALUE (RUN_DIR
relative to the study file), so that no run is repeated. Writes
benchmarks/results/gtpase-<parameter>.{csv,md,png}, the csv with the columns
  parameter,value,number,circularity,v_cm,v_peak,x_cm,t_end,steps,wall_time_s
(value in SI units, number the dimensionless number the scene sets; circularity (5.20),
v_cm (the cell's mean x-velocity) and x_cm (5.19) at the last step, v_peak the largest
v_cm of the run). The figure shows the zero level sets at the last output time, each moved
so that its centroid is at 0 (Fig. 5.5), and the circularity and speed against the
parameter (Fig. 5.6).
"""
import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
import study as study_runner  # noqa: E402  (python/study.py)
from cellphase_results import read_fields, zero_level_set_2d  # noqa: E402
from results_csv import hand_written_notes, write_csv  # noqa: E402
from study_file import load_study  # noqa: E402

COLUMNS = ["parameter", "value", "number", "circularity", "v_cm", "v_peak", "x_cm", "t_end",
           "steps", "wall_time_s"]

# The swept number -> (parameter, SI unit, value from the number) for the units of the demo
# (L 5e-6 m, V 0.14e-6 m/s, eta 10 Pa s): Fa = eta V / (alpha L), Ca = 2 sqrt2 eta V /
# (3 sigma), Be = 4 sqrt2 eta V L^2 / (3 b_N) (docs/scenes.md, units). The demo's numbers
# (Fa 0.05, Ca 0.264, Be 6.6) are the thesis' rounded values for alpha 5.6 N/m^2,
# sigma 5e-6 N/m, b_N 1e-17 J, so the values are scaled from those.
PARAMETERS = {
    "numbers.Fa": ("alpha", "N/m^2", lambda fa: 5.6 * 0.05 / fa),
    "numbers.Ca": ("sigma", "N/m", lambda ca: 5e-6 * 0.264 / ca),
    "numbers.Be": ("b_N", "J", lambda be: 1e-17 * 6.6 / be),
}


def swept_number(study):
    keys = [k for k in study.sweep_keys if k in PARAMETERS]
    if len(keys) != 1:
        raise SystemExit(f"{study.path}: the sweep must vary exactly one of "
                         f"{', '.join(PARAMETERS)} (found {', '.join(study.sweep_keys)})")
    return keys[0]


def final_level_set(run_dir):
    """The zero level set of phi at the last output time (pieces of K x 2 points)."""
    last = None
    for time, points, cells, values in read_fields(run_dir, fields=["phi"]):
        last = (time, points, cells, values["phi"])
    if last is None:
        return None, []
    time, points, cells, phi = last
    return time, zero_level_set_2d(points[:, :2], cells, phi)


def centroid(piece):
    """The area centroid of a closed contour (shoelace formula)."""
    x, y = piece[:, 0], piece[:, 1]
    cross = x * np.roll(y, -1) - np.roll(x, -1) * y
    area = cross.sum() / 2
    return np.array([((x + np.roll(x, -1)) * cross).sum(), ((y + np.roll(y, -1)) * cross).sum()]) \
        / (6 * area)


def borrowed(study, key, extra):
    """Result dicts (as study.collect gives) of the --with members."""
    results = []
    for spec in extra:
        setting, _, run_dir = spec.partition(":")
        k, _, value = setting.partition("=")
        if k != key or not run_dir:
            raise SystemExit(f"--with {spec}: expected {key}=VALUE:RUN_DIR")
        path = (study.path.parent / run_dir).resolve()
        done = path / study_runner.DONE
        if not done.is_file():
            raise SystemExit(f"--with {spec}: {path} is not a finished member (no {done.name})")
        results.append({"name": os.path.relpath(path, study.output), "params": {key: value},
                        "status": "ok", "obs": study_runner.read_observables(path),
                        "wall": json.loads(done.read_text())["wall"]})
    return results


def member_rows(study, key, extra=()):
    name, _, to_value = PARAMETERS[key]
    rows, shapes, missing = [], [], []
    for r in study_runner.collect(study) + borrowed(study, key, extra):
        number = float(r["params"][key])
        if r["status"] != "ok":
            missing.append(f"{key.split('.')[-1]} = {number:g}: {r['status']}")
            continue
        obs = r["obs"]
        rows.append({"parameter": name, "value": to_value(number), "number": number,
                     "circularity": float(obs["circularity"][-1]),
                     "v_cm": float(obs["cell_velocity_x"][-1]),
                     "v_peak": float(np.max(obs["cell_velocity_x"])),
                     "x_cm": float(obs["center_x"][-1]), "t_end": float(obs["time"][-1]),
                     "steps": int(obs["step"][-1]), "wall_time_s": r["wall"]})
        time, pieces = final_level_set(study.output / r["name"])
        shapes.append((rows[-1], time, pieces, obs))
    order = sorted(range(len(rows)), key=lambda i: rows[i]["value"])
    return [rows[i] for i in order], [shapes[i] for i in order], missing


def plot(rows, shapes, key, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    name, unit, _ = PARAMETERS[key]
    fig, axes = plt.subplots(1, 4, figsize=(16, 4), constrained_layout=True)
    cmap = plt.get_cmap("viridis")
    colours = [cmap(i / max(1, len(rows) - 1)) for i in range(len(rows))]
    ax = axes[0]
    for (row, time, pieces, _), colour in zip(shapes, colours):
        if not pieces:
            continue
        # Centred on the shape's own centroid (the largest piece: the cell).
        shift = centroid(max(pieces, key=len))
        for k, piece in enumerate(pieces):
            ax.plot(piece[:, 0] - shift[0], piece[:, 1] - shift[1], color=colour, lw=1.3,
                    label=f"{name} = {row['value']:.3g}" if k == 0 else None)
    ax.set_aspect("equal")
    times = sorted({f"{time:g}" for _, time, pieces, _ in shapes if pieces})
    ax.set(xlabel="x - centroid", ylabel="y - centroid",
           title=f"zero level sets at t = {', '.join(times)}")
    ax.legend(fontsize=7)
    ax = axes[1]
    for (row, _, _, obs), colour in zip(shapes, colours):
        ax.plot(obs["time"], obs["cell_velocity_x"], color=colour, label=f"{row['value']:.3g}")
    ax.set(xlabel="t", ylabel="v_cm", title="speed against time")
    x = [r["value"] for r in rows]
    axes[2].plot(x, [r["circularity"] for r in rows], "o-")
    axes[2].set(xlabel=f"{name} [{unit}]", ylabel="circularity (5.20)",
                title=f"circularity at t = {rows[0]['t_end']:g}")
    axes[3].plot(x, [r["v_cm"] for r in rows], "o-", label=f"at t = {rows[0]['t_end']:g}")
    axes[3].plot(x, [r["v_peak"] for r in rows], "s--", label="peak")
    axes[3].set(xlabel=f"{name} [{unit}]", ylabel="v_cm", title="speed")
    axes[3].legend(fontsize=8)
    if key == "numbers.Be":
        for ax in axes[2:]:
            ax.set_xscale("log")
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_markdown(rows, missing, study, key, path, figure, extra=()):
    name, unit, _ = PARAMETERS[key]
    settings = ", ".join(f"`{k}={v}`" for k, v in study.common.items())
    lines = [f"# The motile GTPase cell against {name} (thesis Figs. 5.5 and 5.6)", "",
             f"Written by `benchmarks/gtpase_shapes.py` from `{os.path.relpath(study.path.resolve(), ROOT)}` "
             f"(the cell of demos/gtpase-motile-cell; every member: {settings}). Circularity "
             f"(5.20), v_cm and x_cm (5.19) at the last step; v_peak the largest v_cm of the run.",
             "", f"| {name} [{unit}] | {key.split('.')[-1]} | circularity | v_cm | v_peak | x_cm "
             f"| t_end | steps | wall s (1 core) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['value']:.3g} | {r['number']:.4g} | {r['circularity']:.4f} | "
                     f"{r['v_cm']:.4f} | {r['v_peak']:.4f} | {r['x_cm']:.3f} | {r['t_end']:g} "
                     f"| {r['steps']} | {r['wall_time_s']:.0f} |")
    if extra:
        lines += ["", "From other studies (the same scene): " + ", ".join(
            f"{spec.split(':')[0]} is `{os.path.relpath((study.path.parent / spec.partition(':')[2]).resolve(), ROOT)}`"
            for spec in extra) + "."]
    if missing:
        lines += ["", "Not finished:", ""] + [f"- {m}" for m in missing]
    lines += ["", f"![shapes and speeds]({figure})", ""]
    notes = hand_written_notes(path)
    if notes:
        lines.append(notes)
    path.write_text("\n".join(lines))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("study", help="a sweep study file of benchmarks/studies/")
    p.add_argument("--run", action="store_true", help="run the members not yet done first")
    p.add_argument("--jobs", type=int, default=1, help="members run at once with --run")
    p.add_argument("--with", dest="extra", action="append", default=[], metavar="KEY=VALUE:RUN_DIR",
                   help="a finished member of another study, the same scene at KEY=VALUE")
    a = p.parse_args(argv)
    study = load_study(a.study)
    key = swept_number(study)
    if a.run:
        subprocess.run([sys.executable, str(ROOT / "python" / "study.py"), "run", str(a.study),
                        "--jobs", str(a.jobs)], check=False)
    rows, shapes, missing = member_rows(study, key, a.extra)
    if not rows:
        raise SystemExit(f"{study.output}: no finished member yet (run with --run)")
    stem = f"gtpase-{PARAMETERS[key][0].lower().replace('_', '')}"
    results = ROOT / "benchmarks" / "results"
    write_csv(results / f"{stem}.csv", COLUMNS, rows)
    plot(rows, shapes, key, results / f"{stem}.png")
    write_markdown(rows, missing, study, key, results / f"{stem}.md", f"{stem}.png", a.extra)
    print((results / f"{stem}.md").read_text())


if __name__ == "__main__":
    main()
