#!/usr/bin/python3
"""Bifurcation diagram of the active polar gel cell (thesis Fig. 6.8) with the study tool:
the stationary speed |v_cell| against the activity 1/Fa for beta = 0 and 0.05, swept at
eps 0.42 (benchmarks/studies/polar-bifurcation.yaml) and at the thesis' eps 0.21
(polar-bifurcation-eps0.21.yaml). Every member stops once v_cell has settled
(numerics.stop_when_settled), at the latest at its end_time.

Usage: /usr/bin/python3 benchmarks/polar_bifurcation.py [STUDY.yaml ...] [--jobs N] [--mpi N]
                                                        [--report-only]

Runs the members not yet done (python/study.py run, one study after the other), then writes
benchmarks/results/polar-bifurcation.csv with the columns
  beta,inv_fa,epsilon,v_cell,settled,t_end,steps,wall_time_s
(v_cell: |mean cell_velocity_x| over the last settling window; settled: 1 if the member
stopped because v_cell settled, 0 if it reached end_time still changing), a table in
polar-bifurcation.md and the diagram polar-bifurcation.png (|v_cell| against 1/Fa, a panel
per eps with 1/Fa_crit of polar-critical.csv, open markers for members that had not
settled). The report's hand-written "## What it shows" section is kept.

The finished members' time series are kept in
benchmarks/results/polar-bifurcation-members/<study> (python/study_archive.py) and put back
into a fresh output directory before the run, so a new machine reruns only what is missing.
"""
import argparse
import csv
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
import study as study_runner  # noqa: E402  (python/study.py)
from results_csv import write_csv, write_report  # noqa: E402
from convergence_table import run_ladder  # noqa: E402  (restore, run and archive any study)

ARCHIVE = ROOT / "benchmarks" / "results" / "polar-bifurcation-members"

COLUMNS = ["beta", "inv_fa", "epsilon", "v_cell", "settled", "t_end", "steps", "wall_time_s"]


def settle_settings(study):
    """over and end_time of the members (the study's `set`)."""
    common = study.common
    return (float(common["numerics.stop_when_settled.over"]),
            float(common["numerics.end_time"]))


def member_rows(study):
    """One row per finished member, and a line for each unfinished one."""
    over, end_time = settle_settings(study)
    rows, missing = [], []
    for r in study_runner.collect(study):
        beta = float(r["params"]["polar_gel.beta"])
        inv_fa = float(r["params"]["polar_gel.activity"])
        if r["status"] != "ok":
            missing.append(f"eps = {float(study.common['numerics.epsilon']):g}, beta = {beta:g}, "
                           f"1/Fa = {inv_fa:g}: {r['status']}")
            continue
        t, v = r["obs"]["time"], r["obs"]["cell_velocity_x"]
        window = [abs(x) for s, x in zip(t, v) if s >= t[-1] - over - 1e-9]
        rows.append({"beta": beta, "inv_fa": inv_fa,
                     "epsilon": float(study.common["numerics.epsilon"]),
                     "v_cell": sum(window) / len(window),
                     "settled": int(float(t[-1]) < end_time - 1e-9),
                     "t_end": float(t[-1]), "steps": int(r["obs"]["step"][-1]),
                     "wall_time_s": r["wall"]})
    return rows, missing


def critical_activities():
    """1/Fa_crit by eps for beta = 0 from polar_critical.py's table, if it is there."""
    path = ROOT / "benchmarks" / "results" / "polar-critical.csv"
    if not path.is_file():
        return {}
    with path.open() as f:
        return {float(r["epsilon"]): float(r["inv_fa_crit"]) for r in csv.DictReader(f)
                if float(r["beta"]) == 0}


def plot(rows, path):
    """|v_cell| against 1/Fa, one panel per eps, one line per beta."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    epsilons = sorted({r["epsilon"] for r in rows}, reverse=True)
    fig, axes = plt.subplots(1, len(epsilons), figsize=(5.0 * len(epsilons), 4), sharex=True,
                             sharey=True, squeeze=False, constrained_layout=True)
    critical = critical_activities()
    for ax, eps in zip(axes[0], epsilons):
        if eps in critical:
            ax.axvline(critical[eps], color="0.6", ls="--", lw=1,
                       label=f"1/Fa_crit = {critical[eps]:.3g} (beta = 0, bisection)")
        for beta in sorted({r["beta"] for r in rows}):
            mine = [r for r in rows if r["beta"] == beta and r["epsilon"] == eps]
            if not mine:
                continue
            line, = ax.plot([r["inv_fa"] for r in mine], [r["v_cell"] for r in mine], "-",
                            label=f"beta = {beta:g}")
            for r in mine:
                ax.plot(r["inv_fa"], r["v_cell"], "o", color=line.get_color(),
                        markerfacecolor=line.get_color() if r["settled"] else "white")
        ax.set_xlabel("activity 1/Fa")
        ax.set_title(f"eps = {eps:g} (open: not settled by t_end)", fontsize=10)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("stationary |v_cell|")
    fig.suptitle("Polar gel cell: bifurcation diagram (thesis Fig. 6.8)", fontsize=11)
    fig.savefig(path, dpi=120)


AT_REST = 0.01  # |v_cell| below this counts as at rest (moving members here: 0.1 and more)


def listed(values):
    return ", ".join(f"{x:g}" for x in values) or "none"


def critical_brackets(rows):
    """For beta = 0 (a pitchfork: P -> -P is a symmetry), the activities between which the
    cell starts to move: the largest 1/Fa at rest (|v_cell| < AT_REST) and the smallest above
    it that moves. For beta > 0 (no such symmetry) the speeds in order."""
    lines = []
    for eps, beta in sorted({(r["epsilon"], r["beta"]) for r in rows}, key=lambda k: (-k[0], k[1])):
        mine = sorted((r for r in rows if r["beta"] == beta and r["epsilon"] == eps),
                      key=lambda r: r["inv_fa"])
        head = f"- eps = {eps:g}, beta = {beta:g}:"
        if beta != 0:
            speeds = ", ".join(f"{r['v_cell']:.3g} ({r['inv_fa']:g})" for r in mine)
            lines.append(f"{head} |v_cell| (1/Fa) = {speeds}.")
            continue
        rest = [r["inv_fa"] for r in mine if r["v_cell"] < AT_REST]
        moving = [r["inv_fa"] for r in mine if r["v_cell"] >= AT_REST
                  and (not rest or r["inv_fa"] > max(rest))]
        if rest and moving:
            lines.append(f"{head} at rest (|v_cell| < {AT_REST:g}) up to 1/Fa = "
                         f"{max(rest):g}, moving from {min(moving):g}: the critical activity "
                         f"lies between them.")
        else:
            lines.append(f"{head} no onset among the finished members: at rest (|v_cell| < "
                         f"{AT_REST:g}) at 1/Fa = {listed(rest)}, moving at "
                         f"{listed(r['inv_fa'] for r in mine if r['v_cell'] >= AT_REST)}.")
    lines.append("- The thesis finds 1/Fa_crit ~ 0.75 at eps = 0.21 for beta = 0, growing with "
                 "eps (Fig. 6.10), and a transition smoothed out for beta > 0 (Fig. 6.8); "
                 "benchmarks/results/polar-critical.md has 1/Fa_crit by bisection.")
    return lines


def write_markdown(rows, missing, study, path):
    """The table; the settling rule is that of `study` (the same in every sweep)."""
    over, end_time = settle_settings(study)
    epsilons = ", ".join(f"{e:g}" for e in sorted({r["epsilon"] for r in rows}, reverse=True))
    lines = [
        "# Bifurcation diagram of the active polar gel cell (thesis Fig. 6.8)",
        "",
        "Written by `benchmarks/polar_bifurcation.py` from "
        f"`benchmarks/studies/polar-bifurcation*.yaml` (eps = {epsilons}; each member stops "
        "once v_cell varies by at most "
        f"{study.common['numerics.stop_when_settled.relative']} of itself or "
        f"{study.common['numerics.stop_when_settled.absolute']} over {over:g} time units, at "
        f"the latest at t = {end_time:g}). v_cell is |mean cell_velocity_x| over the last "
        f"{over:g} time units. A cell coming to rest counts as settled once its speed changes "
        f"by less than the absolute tolerance over the window, so speeds of that order mean "
        f"\"at rest\" (still decaying); a member that reaches t_end unsettled is listed with "
        f"its speed then.",
        "",
        "| eps | beta | 1/Fa | v_cell | settled | t_end | steps | wall s (1 core) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['epsilon']:g} | {r['beta']:g} | {r['inv_fa']:g} | {r['v_cell']:.4g} | "
                     f"{'yes' if r['settled'] else 'no'} | {r['t_end']:g} | {r['steps']} | "
                     f"{r['wall_time_s']:.0f} |")
    lines += [""] + critical_brackets(rows)
    if missing:
        lines += ["", "Not finished:", ""] + [f"- {m}" for m in missing]
    lines += ["", "![diagram](polar-bifurcation.png)", ""]
    write_report(path, lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    studies = ROOT / "benchmarks" / "studies"
    parser.add_argument("studies", nargs="*", default=[
        str(studies / name) for name in (
            "polar-bifurcation.yaml", "polar-bifurcation-eps0.21.yaml")])
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--mpi", type=int, default=1, help="MPI ranks per member")
    parser.add_argument("--report-only", action="store_true")
    args = parser.parse_args(argv)
    rows, missing = [], []
    for path in args.studies:
        study = run_ladder(path, ARCHIVE / Path(path).stem, args)
        more_rows, more_missing = member_rows(study)
        rows += more_rows
        missing += more_missing
    if not rows:
        sys.exit("no member finished (run without --report-only)")
    rows.sort(key=lambda row: (-row["epsilon"], row["beta"], row["inv_fa"]))
    out = ROOT / "benchmarks" / "results"
    write_csv(out / "polar-bifurcation.csv", COLUMNS, rows)
    plot(rows, out / "polar-bifurcation.png")
    write_markdown(rows, missing, study, out / "polar-bifurcation.md")
    for r in rows:
        print(f"eps {r['epsilon']:g}  beta {r['beta']:g}  1/Fa {r['inv_fa']:<5g} "
              f"v_cell {r['v_cell']:.4g}  "
              f"{'settled' if r['settled'] else 'NOT settled'} at t = {r['t_end']:g}")
    for m in missing:
        print("not finished:", m)
    print(f"written: {out / 'polar-bifurcation.csv'}, .md, .png")


if __name__ == "__main__":
    main()
