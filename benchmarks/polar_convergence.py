#!/usr/bin/python3
"""Table 6.2 of the thesis with the study tool: the motile active polar gel cell on
I = [0, 500] for eps = 0.42, 0.30, 0.21, 0.15 with beta = 0 and beta = 0.05
(benchmarks/studies/polar-convergence*.yaml), and the error norms and ROC of x_cm, v_cell and
circularity against the finest finished member of each half.

Usage: /usr/bin/python3 benchmarks/polar_convergence.py [STUDY.yaml ...] [--jobs N] [--mpi N]
                                                        [--report-only]

Runs the studies given (default: both); the other half of the table is reported from
its members on disk.

Runs the members not yet done (python/study.py run; `kill -USR1 <pid of study.py>` stops a
long member with a checkpoint and the next run continues it), then writes
benchmarks/results/polar-convergence.csv with the columns
  beta,epsilon,dofs,wall_time_s,err_xcm,err_vcell,err_circ
polar-convergence.md (a table per beta with the ROC of each quantity, and the cost of a step
split between flow, orientation field, phase field and remeshing) and
polar-convergence-beta<beta>.png (the quantities against time). A cell that moves to the
left is reflected about its initial centre (x_cm -> 2 x_cm(0) - x_cm, v_cell -> -v_cell), as
the thesis does. dt = eps / 3 on every member: the members have about 3570, 5000, 7140
and 10000 steps. The studies refine the interior one level less than the interface band
and reuse the orientation field's factors (see the study files): the eps 0.42 members have
54k dofs and took 20 min on one core each, side by side. With --mpi 2 on 2 cores the
eps 0.21 member costs about 0.7-0.8 s per step on a machine where the splay demo's
settings take 1.27 s (demos/polar-gel-splay/README.md, "Faster at epsilon = 0.21"), the
eps 0.15 member several hours (stop it with kill -USR1 and continue it later on the same
machine).

The finished members' time series are kept in
benchmarks/results/polar-convergence-members/<study> (python/study_archive.py) and put back
into a fresh output directory before the run, so the members of an earlier session are not
rerun on a new machine.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from study_report import convergence_errors  # noqa: E402
from convergence_table import (add_arguments, cost_table, error_rows,  # noqa: E402
                               member_results, plot_members, run_ladder, table_lines,
                               write_results)

STUDIES = [ROOT / "benchmarks" / "studies" / f"polar-convergence{s}.yaml" for s in ("", "-beta0.05")]
ARCHIVE = ROOT / "benchmarks" / "results" / "polar-convergence-members"
QUANTITIES = [("center_x", "err_xcm", "x_cm"), ("cell_velocity_x", "err_vcell", "v_cell"),
              ("circularity", "err_circ", "circularity")]
COLUMNS = ["beta", "epsilon", "dofs", "wall_time_s", "err_xcm", "err_vcell", "err_circ"]
# The cell (radius 5) nears the periodic face x = 160 first in the finest, fastest member.
# The errors are also given on the time before any member's front x_cm + 5 gets within 3 of
# the face (the band reaches it about 1 later): free of whatever the crossing does
# (benchmarks/results/periodic-crossing.md).
RADIUS, FACE, MARGIN = 5.0, 160.0, 3.0


def reflect_left_movers(results):
    """Members whose cell ends left of its start, mirrored about the initial centre: the
    thesis compares the motion, whichever way the instability chose (Fig. 6.9)."""
    mirrored = []
    for r in results:
        x = np.asarray(r["obs"]["center_x"], dtype=float)
        if x[-1] < x[0]:
            r["obs"]["center_x"] = 2 * x[0] - x
            r["obs"]["cell_velocity_x"] = -np.asarray(r["obs"]["cell_velocity_x"], dtype=float)
            mirrored.append(f"eps = {r['eps']:g}")
    return mirrored


def time_before_the_face(results):
    """The last whole time before any member's front gets within MARGIN of the face."""
    first = []
    for r in results:
        t = np.asarray(r["obs"]["time"], dtype=float)
        near = np.asarray(r["obs"]["center_x"], dtype=float) + RADIUS >= FACE - MARGIN
        first.append(t[np.argmax(near)] if near.any() else t[-1])
    return float(np.floor(min(first)))


def errors_before_the_face(results):
    """The table's errors and ROC on [0, time_before_the_face] only."""
    until = time_before_the_face(results)
    cut = []
    for r in results:
        t = np.asarray(r["obs"]["time"], dtype=float)
        keep = t <= until + 1e-9
        obs = {k: np.asarray(v, dtype=float)[keep] for k, v in r["obs"].items()
               if k in ("time",) + tuple(q for q, _, _ in QUANTITIES)}
        cut.append({**r, "obs": obs})
    errors = convergence_errors(cut, [q for q, _, _ in QUANTITIES])
    lines = ["", f"Errors on [0, {until:g}], before any member's cell nears the periodic face "
             f"(its front x_cm + {RADIUS:g} within {MARGIN:g} of x = {FACE:g}):", "",
             "| eps | " + " | ".join(f"{n} err | ROC" for _, _, n in QUANTITIES) + " |",
             "|---" * (1 + 2 * len(QUANTITIES)) + "|"]
    for i, r in enumerate(cut[:-1]):
        cells = [f"{r['eps']:g}"]
        for q, _, _ in QUANTITIES:
            e, roc = errors[q][i]
            cells += [f"{e:.4f}", "-" if roc != roc else f"{roc:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def cost_split(results):
    """Mean wall time per step and its split: wall_flow and wall_polar are parts of the
    assembly, factorisation and solve columns, the rest of those is the phase field;
    remeshing is apart."""
    return [""] + cost_table(results, ["wall_flow", "wall_polar"],
                             [("flow", "wall_flow"), ("orientation", "wall_polar"),
                              ("phase field", "phase"), ("remesh", "wall_remesh")])


def half_of_table(study, args):
    """The rows of polar-convergence.csv and the report's section for one value of beta."""
    beta = study.common.get("polar_gel.beta", 0)
    results, missing = member_results(study, minimum=0)
    title = f"## beta = {beta:g}"
    if len(results) < 2:
        lines = [title, "", f"Fewer than two members finished ({len(results)}): no errors yet."]
        lines += [f"- eps = {r['eps']:g}: finished at t = {r['obs']['time'][-1]:g} after "
                  f"{len(r['obs']['time']) - 1} steps in {r['wall']:.0f} s; v_cell "
                  f"{float(r['obs']['cell_velocity_x'][-1]):.4g}, x_cm "
                  f"{float(r['obs']['center_x'][-1]):.4g}, circularity "
                  f"{float(r['obs']['circularity'][-1]):.4g}" for r in results]
        lines += [f"- {line}" for _, line in missing]
        return [], lines + (cost_split(results) if results else []) + [""]
    mirrored = reflect_left_movers(results)
    rows, errors = error_rows(results, QUANTITIES, extra={"beta": beta})
    lines = [title, ""]
    lines += [f"- Reflected (moved left): {', '.join(mirrored)}.", ""] if mirrored else []
    lines += table_lines(results, rows, errors, QUANTITIES, missing)
    lines += errors_before_the_face(results)
    lines += cost_split(results)
    png = f"polar-convergence-beta{beta:g}.png"
    plot_members(results, QUANTITIES, args.results / png,
                 f"Motile polar gel cell, beta = {beta:g}: the members of Table 6.2")
    lines += ["", f"![the members against time]({png})", ""]
    return rows, lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("studies", nargs="*", type=Path, default=STUDIES)
    add_arguments(parser)
    parser.add_argument("--archive", type=Path, default=ARCHIVE,
                        help="finished members' time series, kept in the repository, one "
                             f"folder per study (default {ARCHIVE.relative_to(ROOT)})")
    args = parser.parse_args()
    args.results.mkdir(parents=True, exist_ok=True)
    all_rows = []
    # Both halves of the table stay in the report when only one study is run: the other
    # is reported from its members on disk.
    given = [p.resolve() for p in args.studies]
    studies = [p.resolve() for p in STUDIES] + [p for p in given if p not in STUDIES]
    lines = ["# Table 6.2: convergence of the motile polar gel cell in epsilon", "",
             "Studies: " + ", ".join(f"`{p.relative_to(ROOT) if p.is_relative_to(ROOT) else p}`"
                                     for p in studies)
             + "; relative error norm of section 5.3 against the finest finished member of "
               "each half, ROC between neighbouring members. Cost per step: mean over the "
               "steps, shares of the step's wall time.", ""]
    for path in studies:
        run_args = argparse.Namespace(**{**vars(args), "report_only": args.report_only
                                         or path not in given})
        study = run_ladder(path, args.archive / path.stem, run_args)
        rows, section = half_of_table(study, args)
        all_rows += rows
        lines += section
    write_results(args.results, "polar-convergence", all_rows, COLUMNS, lines)

if __name__ == "__main__":
    main()
