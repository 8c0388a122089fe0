#!/usr/bin/python3
"""The moving polar gel cell as a squirmer (thesis section 6.5, Table 6.3, Fig. 6.14).

Runs benchmarks/studies/polar-squirmer.yaml with the study tool (beta = 0.05, 1/Fa = 0.5,
0.75, 1, each member until its speed has settled), then fits on each member's final fields
(python/squirmer_fit.py): the tangential surface velocity in the co-moving frame to the
squirmer profile (6.18), n1 (sin a + m sin 2a), and the velocity outside r = 5 to the far
field (6.19) (v_cell, Stokeslet A_st, stresslet A_str, source dipole A_sd).

Usage: /usr/bin/python3 benchmarks/polar_squirmer.py [--study STUDY.yaml] [--jobs N]
                                                     [--report-only]

The default study runs at eps 0.42; benchmarks/studies/polar-squirmer-eps0.21.yaml runs the
same members at the thesis' eps 0.21. The result files are named after the study
(polar-squirmer*.{csv,md,png}; below for the default study).

Writes benchmarks/results/polar-squirmer.csv with the columns
  inv_fa,v_cell,n1,m,A_st,A_str,A_sd,v_cell_fit,t_end,settled
(v_cell: the phi~-weighted mean x velocity of the final state; v_cell_fit: the far field's
uniform part), polar-squirmer.md (beside the thesis' Table 6.3 and its fitted n1, m),
polar-squirmer.png (the profiles and their fits, as Fig. 6.14) and polar-squirmer-shapes.png
(the stationary shapes: |P| with its direction, and the co-moving velocity, as Fig. 6.15).
The report's hand-written "## What it shows" section is kept.
"""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
import study as study_runner  # noqa: E402  (python/study.py)
import squirmer_fit as sq  # noqa: E402
from study_file import load_study  # noqa: E402
from results_csv import write_csv, write_report  # noqa: E402

STUDY = ROOT / "benchmarks" / "studies" / "polar-squirmer.yaml"
RESULTS = ROOT / "benchmarks" / "results"
COLUMNS = ["inv_fa", "v_cell", "n1", "m", "A_st", "A_str", "A_sd", "v_cell_fit", "t_end",
           "settled"]
# Thesis section 6.5 (eps 0.21): Table 6.3, and n1, m of the fits of Fig. 6.14
THESIS = {0.5: {"v_cell": 0.0294, "A_st": 0.0387, "A_str": -0.3541, "A_sd": 12.5882,
                "n1": 0.086, "m": 0.357},
          0.75: {"v_cell": 0.0701, "A_st": 0.0872, "A_str": -0.1744, "A_sd": 28.8854,
                 "n1": 0.172, "m": 0.059},
          1.0: {"v_cell": 0.1089, "A_st": 0.1460, "A_str": 0.3910, "A_sd": 47.3611,
                "n1": 0.291, "m": -0.139}}


def fit_member(run_dir):
    """The fits on the member's last output frame, and the profile samples."""
    t, points, cells, phi, v = sq._frame(run_dir, None, "phi", "v")
    centre, v_cell = sq.cell_centre_and_velocity(points, cells, phi, v)
    alpha, vT = sq.tangential_profile(points, cells, phi, v, centre, v_cell)
    n1, m = sq.fit_squirmer_profile(alpha, vT)
    x, u = sq.far_field_samples(points, phi, v, centre, v_cell, 5.0)
    far = sq.fit_far_field(x, u, 5.0)
    return ({"v_cell": v_cell, "n1": n1, "m": m, "A_st": far["A_st"], "A_str": far["A_str"],
             "A_sd": far["A_sd"], "v_cell_fit": far["v_cell"], "t_end": t}, (alpha, vT))


def plot(rows, profiles, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4), constrained_layout=True)
    a = np.linspace(0, 2 * np.pi, 200)
    for r in rows:
        alpha, vT = profiles[r["inv_fa"]]
        line, = ax.plot(alpha, vT, "--", lw=1, label=f"1/Fa = {r['inv_fa']:g}: simulation")
        ax.plot(a, sq.squirmer_profile(a, r["n1"], r["m"]), "-", color=line.get_color(),
                label=f"fit n1 = {r['n1']:.3f}, m = {r['m']:.3f}")
    ax.set_xlabel("polar angle alpha (0: front)")
    ax.set_ylabel("tangential velocity v_T (co-moving)")
    ax.set_title("Surface velocity and squirmer fit (6.18), beta = 0.05", fontsize=10)
    ax.legend(fontsize=7)
    fig.savefig(path, dpi=120)


def plot_shapes(rows, run_dirs, path):
    """Fig. 6.15: per member the final |P| with P's direction, and |v - v_cell e1| with its
    direction, around the cell."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    from plot_polar_gel import draw_panel
    from cellphase_results import read_fields
    fig, axes = plt.subplots(2, len(rows), figsize=(3.4 * len(rows), 5.2), squeeze=False,
                             constrained_layout=True)
    for j, r in enumerate(rows):
        _, points, cells, values = list(read_fields(run_dirs[r["inv_fa"]], ["phi", "P", "v"]))[-1]
        tri = mtri.Triangulation(points[:, 0], points[:, 1], cells)
        phi = values["phi"]
        inside = np.clip((1 + phi) / 2, 0, 1)
        centre = (points[:, :2] * inside[:, None]).sum(axis=0) / inside.sum()
        co_moving = values["v"][:, :2] - np.array([r["v_cell"], 0.0])
        for i, (label, field) in enumerate([("|P|", values["P"][:, :2]),
                                            ("|v - v_cell e1|", co_moving)]):
            ax = axes[i][j]
            draw_panel(fig, ax, tri, phi, field, centre, 8.0)
            if i == 0:
                ax.set_title(f"1/Fa = {r['inv_fa']:g}, v_cell = {r['v_cell']:.3f}", fontsize=9)
            if j == 0:
                ax.set_ylabel(label)
    fig.savefig(path, dpi=110)


def write_markdown(rows, study, study_file, path):
    c = study.common
    name = path.stem
    lines = ["# The polar gel cell as a squirmer (thesis Table 6.3, Fig. 6.14)", "",
             "Written by `benchmarks/polar_squirmer.py` from "
             f"`benchmarks/studies/{study_file.name}`: beta = 0.05, channel [0, 160] x "
             f"[0, 40], eps = {c['numerics.epsilon']} (the thesis: 0.21), each member run "
             "until v_cell varied by at most "
             f"{float(c['numerics.stop_when_settled.relative']) * 100:g} % over "
             f"{c['numerics.stop_when_settled.over']} time units (at the latest t = "
             f"{c['numerics.end_time']}). Fits on the final state: the surface profile "
             "(6.18) on phi = 0 and the far field (6.19) outside r = 5, both in the "
             "co-moving frame (python/squirmer_fit.py). Thesis values in parentheses.", "",
             "| 1/Fa | v_cell | n1 | m | A_st | A_str | A_sd | settled at t | v_cell over the "
             "last 50 time units |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        th = THESIS.get(r["inv_fa"], {})

        def cell(key, fmt):
            mine = format(r[key], fmt)
            return f"{mine} ({format(th[key], fmt)})" if key in th else mine
        lines.append(f"| {r['inv_fa']:g} | {cell('v_cell', '.4f')} | {cell('n1', '.3f')} | "
                     f"{cell('m', '.3f')} | {cell('A_st', '.4f')} | {cell('A_str', '.4f')} | "
                     f"{cell('A_sd', '.3f')} | "
                     f"{r['t_end']:g}{'' if r['settled'] else ' (not settled)'} | "
                     f"{r['v_range'][0]:.4f} .. {r['v_range'][1]:.4f} |")
    kinds = []
    for r in rows:
        kind = "puller" if r["m"] > 0.1 else "pusher" if r["m"] < -0.1 else "near neutral"
        kinds.append(f"1/Fa = {r['inv_fa']:g}: m = {r['m']:.3f} ({kind}), "
                     f"A_str = {r['A_str']:.3f}")
    lines += ["", "- " + "; ".join(kinds) + ".",
              "- A member that reached the end time unsettled has moved within the range of "
              "the last column over its last 50 time units; its fits use the final state.",
              "- The thesis finds pullers for 1/Fa <= 0.5 (m > 0, A_str < 0), near-neutral "
              "swimmers at 0.75 and pushers for 1/Fa >= 1 (m < 0, A_str > 0), with the far "
              "field dominated by the Stokeslet.", "",
              f"![profiles and fits]({name}.png)", "",
              "Stationary shapes (Fig. 6.15), moving to the right: |P| and the direction of "
              "P, and the velocity in the co-moving frame.", "",
              f"![stationary shapes]({name}-shapes.png)", ""]
    write_report(path, lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--study", default=str(STUDY))
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--report-only", action="store_true",
                        help="fit the members already run")
    args = parser.parse_args(argv)
    if not args.report_only:
        subprocess.run([sys.executable, str(ROOT / "python" / "study.py"), "run", args.study,
                        "--jobs", str(args.jobs)], check=False)
    study = load_study(args.study)
    end_time = float(study.common["numerics.end_time"])
    rows, profiles, run_dirs = [], {}, {}
    for r in study_runner.collect(study):
        inv_fa = float(r["params"]["polar_gel.activity"])
        if r["status"] != "ok":
            print(f"1/Fa = {inv_fa:g}: {r['status']}")
            continue
        row, profile = fit_member(study.output / r["name"])
        row["inv_fa"] = inv_fa
        row["settled"] = int(row["t_end"] < end_time - 1e-9)
        t, v = r["obs"]["time"], r["obs"]["cell_velocity_x"]  # the spread of the last 50
        last = [x for s_, x in zip(t, v) if s_ >= t[-1] - 50 - 1e-9]
        row["v_range"] = (min(last), max(last))
        rows.append(row)
        profiles[inv_fa] = profile
        run_dirs[inv_fa] = study.output / r["name"]
    if not rows:
        sys.exit("no member finished (run without --report-only)")
    rows.sort(key=lambda r: r["inv_fa"])
    name = Path(args.study).stem  # polar-squirmer, polar-squirmer-eps0.21
    write_csv(RESULTS / f"{name}.csv", COLUMNS, rows)
    plot(rows, profiles, RESULTS / f"{name}.png")
    plot_shapes(rows, run_dirs, RESULTS / f"{name}-shapes.png")
    write_markdown(rows, study, Path(args.study), RESULTS / f"{name}.md")
    for r in rows:
        print(f"1/Fa {r['inv_fa']:<5g} v_cell {r['v_cell']:.4f}  n1 {r['n1']:.3f}  m {r['m']:+.3f}"
              f"  A_st {r['A_st']:.4f}  A_str {r['A_str']:+.4f}  A_sd {r['A_sd']:.3f}")
    print(f"written: {RESULTS / name}.csv, .md, .png")


if __name__ == "__main__":
    main()
