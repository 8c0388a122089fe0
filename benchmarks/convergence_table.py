"""The parts shared by the convergence benchmarks (Table 5.2, benchmarks/gtpase_convergence.py;
Table 6.2, benchmarks/polar_convergence.py): run a ladder study whose finished members are
kept in the repository, read the finished members, and write the table of error norms and
ROC against the finest finished member (relative error norm of thesis section 5.3).

A quantity is a tuple (observables.csv column, CSV column of its error, name in the table).
"""
import csv
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
import study as study_runner  # noqa: E402  (python/study.py)
from study_file import load_study  # noqa: E402
from study_report import convergence_errors  # noqa: E402
from study_archive import archive_members, restore_members  # noqa: E402
from results_csv import hand_written_notes  # noqa: E402


def add_arguments(parser):
    """The options every convergence benchmark takes."""
    parser.add_argument("--jobs", type=int, default=1, help="members run at once")
    parser.add_argument("--mpi", type=int, default=1, help="MPI ranks per member")
    parser.add_argument("--report-only", action="store_true",
                        help="only write the report from the members on disk")
    parser.add_argument("--results", type=Path, default=ROOT / "benchmarks" / "results")


def run_ladder(study_path, archive, args):
    """Put the archived members back, run the members not yet done (unless --report-only)
    and archive the finished ones. Returns the study (a ladder's or a sweep's)."""
    study = load_study(study_path)
    restored, skipped = restore_members(study, archive)
    for name in restored:
        print(f"{name}: restored from {archive}")
    for name, why in skipped:
        print(f"{name}: not restored from {archive}: {why}")
    if not args.report_only:
        subprocess.run([sys.executable, str(ROOT / "python" / "study.py"), "run", str(study_path),
                        "--jobs", str(args.jobs), "--mpi", str(args.mpi)], check=False)
        # (exit 1: a member failed or was stopped; the table is made of the finished ones)
    archive_members(study, archive)
    return study


def member_results(study, minimum=2):
    """The finished members, coarsest first, and a line for each unfinished one (the study
    tool's own reading of its run directories and markers)."""
    results, missing = [], []
    for r in study_runner.collect(study):
        if r["status"] == "ok":
            results.append(r)
            continue
        at = f"at t = {float(r['obs']['time'][-1]):g}, step {int(r['obs']['step'][-1])}; " \
            if r["obs"] is not None else ""
        missing.append((r["eps"], f"eps = {r['eps']:g}: not finished ({at}{r['status']})"))
    if len(results) < minimum:
        sys.exit(f"{study.output}: fewer than {minimum} members finished "
                 "(run without --report-only)")
    return sorted(results, key=lambda r: -r["eps"]), missing


def error_rows(results, quantities, extra=None):
    """One CSV row per member (errors empty for the reference) and the errors with ROC."""
    errors = convergence_errors(results, [q for q, _, _ in quantities])
    rows = []
    for i, r in enumerate(results):
        row = {**(extra or {}), "epsilon": r["eps"], "dofs": int(r["obs"]["dofs"][-1]),
               "steps": len(r["obs"]["time"]) - 1, "wall_time_s": r["wall"]}
        for q, column, _ in quantities:
            row[column] = errors[q][i][0] if i < len(results) - 1 else ""
        rows.append(row)
    return rows, errors


def table_lines(results, rows, errors, quantities, missing):
    """The unfinished members, then the table: eps, dofs, steps, wall s, error and ROC of
    each quantity."""
    lines = [f"- {line}" for _, line in missing]
    if any(eps < results[-1]["eps"] for eps, _ in missing):
        lines.append("- The reference is therefore not yet the finest member of the ladder.")
    lines += [""] if missing else []
    lines += ["| eps | dofs | steps | wall s | "
              + " | ".join(f"{n} err | ROC" for _, _, n in quantities) + " |",
              "|---" * (4 + 2 * len(quantities)) + "|"]
    for i, (r, row) in enumerate(zip(results, rows)):
        cells = [f"{r['eps']:g}", str(row["dofs"]), str(row["steps"]),
                 f"{row['wall_time_s']:.0f}" if row["wall_time_s"] else "-"]
        for q, _, _ in quantities:
            if i < len(results) - 1:
                e, roc = errors[q][i]
                cells += [f"{e:.4f}", "-" if roc != roc else f"{roc:.2f}"]
            else:
                cells += ["(reference)", ""]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def cost_table(results, sub_problems, columns):
    """Mean wall time per step of every member and its shares. `sub_problems`: the wall_*
    columns of the sub-problems timed inside the assembly, factorisation and solve columns;
    the rest of those is the phase field ("phase"). `columns`: (heading, part) in table
    order, a part being one of those columns, "phase", "wall_remesh" or "wall_factorise"."""
    lines = ["| eps | dofs | ranks | s/step | " + " | ".join(h for h, _ in columns) + " |",
             "|---" * (4 + len(columns)) + "|"]
    for r in results:
        o = {k: np.asarray(v[1:], dtype=float) for k, v in r["obs"].items()}
        solve = o["wall_assembly"] + o["wall_factorise"] + o["wall_solve"]
        total = solve + o["wall_remesh"] + o["wall_output"]
        parts = {k: o[k] for k in [*sub_problems, "wall_remesh", "wall_factorise"]}
        parts["phase"] = solve - sum(o[k] for k in sub_problems)
        shares = " | ".join(f"{100 * parts[k].sum() / total.sum():.0f} %" for _, k in columns)
        lines.append(f"| {r['eps']:g} | {int(r['obs']['dofs'][-1])} | {r.get('ranks', 1)} | "
                     f"{total.mean():.3f} | {shares} |")
    return lines


def plot_members(results, quantities, path, title):
    """Each quantity against time, one line per member."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    columns = 2
    rows = (len(quantities) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(9, 3 * rows), constrained_layout=True,
                             squeeze=False)
    for ax, (q, _, name) in zip(axes.flat, quantities):
        for r in results:
            ax.plot(r["obs"]["time"], r["obs"][q], label=f"eps = {r['eps']:g}")
        ax.set_xlabel("t")
        ax.set_title(name)
    for ax in list(axes.flat)[len(quantities):]:
        ax.set_visible(False)
    axes[0][0].legend()
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_results(results_dir, stem, rows, columns, lines):
    """<stem>.csv from the rows (only the given columns) and <stem>.md from the lines, keeping
    the report's hand-written discussion; the lines are printed too."""
    with open(results_dir / f"{stem}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    report = results_dir / f"{stem}.md"
    notes = hand_written_notes(report)
    print("\n".join(lines))
    if notes:
        lines = lines + ["", notes.rstrip("\n")]
    report.write_text("\n".join(lines) + "\n")
