#!/usr/bin/python3
"""Table 5.2 of the thesis with the study tool: the motile GTPase cell on I = [0, 3.5] for
eps = 0.06, 0.042, 0.03, 0.021 (benchmarks/studies/gtpase-convergence.yaml), and the error
norms and ROC of x_cm, v_cm, circularity and Helfrich energy against the finest member.

Usage: /usr/bin/python3 benchmarks/gtpase_convergence.py [STUDY.yaml] [--jobs N] [--mpi N]
                                                         [--report-only]

Runs the members not yet done (python/study.py run; `kill -USR1 <pid of study.py>` stops a
long member with a checkpoint and the next run continues it), then writes, beside the
study's own report, benchmarks/results/gtpase-convergence.csv with the columns
  epsilon,dofs,steps,wall_time_s,err_xcm,err_vcm,err_circ,err_energy
gtpase-convergence.md (the table with the ROC of each quantity, and the cost of a step
split between the sub-problems) and gtpase-convergence.png (the quantities against time).
The finest finished member is the reference (its errors are empty); unfinished members are
listed above the table. With --mpi 2 on 2 cores the eps = 0.03 member takes about
37 min (benchmarks/results/gtpase-convergence.md, "What it shows"), the coarser ones 9 and
17 min, the 0.021 member about 85 min. Without `flow.coupling_stabilisation`
the 0.021 member fails at step 72: the ladder's dt ~ eps exceeds the split's time step
limit there (about 100 h^3, same report); the study gives every member beta = 0.02, which
lifts it (docs/scenes.md).

The finished members' time series are kept in benchmarks/results/gtpase-convergence-members
(python/study_archive.py) and put back into a fresh output directory before the run, so
the members of an earlier session are not rerun on a new machine.
"""
import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from convergence_table import (add_arguments, cost_table, error_rows,  # noqa: E402
                               member_results, plot_members, run_ladder, table_lines,
                               write_results)

ARCHIVE = ROOT / "benchmarks" / "results" / "gtpase-convergence-members"
QUANTITIES = [("center_x", "err_xcm", "x_cm"), ("cell_velocity_x", "err_vcm", "v_cm"),
              ("circularity", "err_circ", "circularity"), ("helfrich_energy", "err_energy",
                                                          "Helfrich energy")]


def cost_split(results):
    """Mean wall time per step of every member and how it splits between the sub-problems:
    wall_flow and wall_rd are parts of the assembly, factorisation and solve columns, the
    rest of those is the phase field (with its volume multiplier); remeshing is apart."""
    return ["", "## Cost per step", "",
            "Mean over the steps; shares of the step's wall time (the sum of its parts).", ""] + \
        cost_table(results, ["wall_flow", "wall_rd"],
                   [("flow", "wall_flow"), ("phase field", "phase"),
                    ("reaction-diffusion", "wall_rd"), ("remesh", "wall_remesh"),
                    ("factorisation (all)", "wall_factorise")])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study", nargs="?", type=Path,
                        default=ROOT / "benchmarks" / "studies" / "gtpase-convergence.yaml")
    add_arguments(parser)
    parser.add_argument("--archive", type=Path, default=ARCHIVE,
                        help="finished members' time series, kept in the repository "
                             f"(default {ARCHIVE.relative_to(ROOT)})")
    args = parser.parse_args()
    study = run_ladder(args.study, args.archive, args)
    results, missing = member_results(study)
    rows, errors = error_rows(results, QUANTITIES)
    args.results.mkdir(parents=True, exist_ok=True)
    lines = ["# Table 5.2: convergence of the motile GTPase cell in epsilon", "",
             f"Study: `{args.study.relative_to(ROOT) if args.study.is_relative_to(ROOT) else args.study}`; "
             "relative error norm of section 5.3 against the finest finished member, ROC "
             "between neighbouring members.", ""]
    lines += table_lines(results, rows, errors, QUANTITIES, missing)
    lines += cost_split(results)
    plot_members(results, QUANTITIES, args.results / "gtpase-convergence.png",
                 "Motile GTPase cell: the members of Table 5.2")
    lines += ["", "![the members against time](gtpase-convergence.png)"]
    write_results(args.results, "gtpase-convergence", rows, list(rows[0]), lines)


if __name__ == "__main__":
    main()
