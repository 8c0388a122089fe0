#!/usr/bin/python3
"""Table 5.2 of the thesis with the study tool: the motile GTPase cell on I = [0, 3.5] for
eps = 0.06, 0.042, 0.03, 0.021 (benchmarks/studies/gtpase-convergence.yaml), and the error
norms and ROC of x_cm, v_cm, circularity and Helfrich energy against the finest member.

Usage: /usr/bin/python3 benchmarks/gtpase_convergence.py [STUDY.yaml] [--jobs N] [--report-only]

Runs the members not yet done (python/study.py run), then writes, beside the study's own
report, benchmarks/results/gtpase-convergence.csv with the columns
  epsilon,dofs,steps,wall_time_s,err_xcm,err_vcm,err_circ,err_energy
and gtpase-convergence.md (the table with the ROC of each quantity). The finest member is
the reference (its errors are empty). The members take long: on 2 cores about 1 h for
eps = 0.06 and several hours for the finer ones.
"""
import argparse
import csv
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from cellphase_results import read_observables  # noqa: E402
from study_file import load_study  # noqa: E402
from study_report import convergence_errors  # noqa: E402

QUANTITIES = [("center_x", "err_xcm", "x_cm"), ("cell_velocity_x", "err_vcm", "v_cm"),
              ("circularity", "err_circ", "circularity"), ("helfrich_energy", "err_energy",
                                                          "Helfrich energy")]


def member_results(study):
    results = []
    for m in study.members:
        run_dir = study.output / m.name
        done = run_dir / "done"
        if not done.exists():
            sys.exit(f"{run_dir}: not finished (run without --report-only first)")
        info = json.loads(done.read_text())
        results.append({"name": m.name, "eps": m.eps, "obs": read_observables(run_dir),
                        "status": "ok", "wall": info.get("wall")})
    return sorted(results, key=lambda r: -r["eps"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study", nargs="?", type=Path,
                        default=ROOT / "benchmarks" / "studies" / "gtpase-convergence.yaml")
    parser.add_argument("--jobs", type=int, default=1, help="members run at once")
    parser.add_argument("--mpi", type=int, default=1, help="MPI ranks per member")
    parser.add_argument("--report-only", action="store_true")
    parser.add_argument("--results", type=Path, default=ROOT / "benchmarks" / "results")
    args = parser.parse_args()
    if not args.report_only:
        subprocess.run([sys.executable, str(ROOT / "python" / "study.py"), "run", str(args.study),
                        "--jobs", str(args.jobs), "--mpi", str(args.mpi)], check=True)
    study = load_study(args.study)
    results = member_results(study)
    errors = convergence_errors(results, [q for q, _, _ in QUANTITIES])
    args.results.mkdir(parents=True, exist_ok=True)
    rows = []
    for i, r in enumerate(results):
        row = {"epsilon": r["eps"], "dofs": int(r["obs"]["dofs"][-1]),
               "steps": len(r["obs"]["time"]) - 1, "wall_time_s": r["wall"]}
        for q, column, _ in QUANTITIES:
            row[column] = errors[q][i][0] if i < len(results) - 1 else ""
        rows.append(row)
    with open(args.results / "gtpase-convergence.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["# Table 5.2: convergence of the motile GTPase cell in epsilon", "",
             f"Study: `{args.study.relative_to(ROOT) if args.study.is_relative_to(ROOT) else args.study}`; "
             "relative error norm of section 5.3 against the finest member, ROC between "
             "neighbouring members.", "",
             "| eps | dofs | steps | wall s | " + " | ".join(f"{n} err | ROC" for _, _, n in QUANTITIES) + " |",
             "|---" * (4 + 2 * len(QUANTITIES)) + "|"]
    for i, (r, row) in enumerate(zip(results, rows)):
        cells = [f"{r['eps']:g}", str(row["dofs"]), str(row["steps"]),
                 f"{row['wall_time_s']:.0f}" if row["wall_time_s"] else "-"]
        for q, _, _ in QUANTITIES:
            if i < len(results) - 1:
                e, roc = errors[q][i]
                cells += [f"{e:.4f}", "-" if roc != roc else f"{roc:.2f}"]
            else:
                cells += ["(reference)", ""]
        lines.append("| " + " | ".join(cells) + " |")
    (args.results / "gtpase-convergence.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
