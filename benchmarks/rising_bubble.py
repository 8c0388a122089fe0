#!/usr/bin/python3
"""Rising bubble benchmark of Hysing et al. (2009), test cases 1 and 2.

Runs demos/rising-bubble-case<N>/scene.yaml at mesh levels (epsilon, and with it the finest
cell, and the time step smaller by sqrt(2) from level to level) to t = 3 and writes:
  benchmarks/results/rising-bubble-case<N>.csv   the benchmark quantities per level
  benchmarks/results/rising-bubble-case<N>.md    tables against the published values
  benchmarks/results/rising-bubble-case<N>.png   circularity, rise velocity and centre of
                                                 mass over time, published extrema marked
The quantities follow the benchmark's definitions: circularity (perimeter of the
area-equivalent circle over the perimeter of the bubble), rise velocity (mean vertical
velocity over the bubble), centre of mass; the bubble is the region phi > 0 weighted by
(1 + phi)/2. For case 2 the rise velocity has two maxima; the first is reported.

Usage: /usr/bin/python3 benchmarks/rising_bubble.py [--case 1 2] [--levels 0 1 2]
                                                     [--end-time T] [--ranks N] [--exe PATH]
                                                     [--report-only]
"""
import argparse
import csv
import datetime
import math
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXE = ROOT / "build" / "cellphase"
WORK = ROOT / "output" / "benchmarks" / "rising-bubble"
RESULTS = ROOT / "benchmarks" / "results"

# Published benchmark quantities (Hysing et al., Int. J. Numer. Meth. Fluids 60 (2009)
# 1259-1288, tables of the three groups TP2D, FreeLIFE and MooNMD). The reference is the
# MooNMD value (the ALE code with a sharp interface); `spread` is the range of the three.
REFERENCE = {
    1: {"circularity_min": (0.9013, (0.9011, 0.9013)),
        "t_circularity_min": (1.9041, (1.8750, 1.9041)),
        "rise_velocity_max": (0.2417, (0.2417, 0.2421)),
        "t_rise_velocity_max": (0.9213, (0.9213, 0.9313)),
        "y_center_final": (1.0813, (1.0799, 1.0817))},
    2: {"circularity_min": (0.5144, (0.4647, 0.5869)),
        "t_circularity_min": (3.0000, (2.4004, 3.0000)),
        "rise_velocity_max": (0.2502, (0.2502, 0.2524)),
        "t_rise_velocity_max": (0.7317, (0.7281, 0.7332)),
        "y_center_final": (1.1376, (1.1249, 1.1380))},
}
QUANTITIES = ["circularity_min", "t_circularity_min", "rise_velocity_max",
              "t_rise_velocity_max", "y_center_final"]
CSV_COLUMNS = ["level", "dofs", "wall_time_s"] + QUANTITIES


# Points across the interface for every level. At level 1 (eps = 0.0141, t <= 1.2) the
# rise velocity changed by 6e-5 and the circularity by 3e-4 from 2 to 4 points, and by
# 1e-6 and 2e-5 from 4 to 8; a base mesh of 10 x 20 instead of 14 x 28 changed them by
# 1e-5 and 7e-5. The error against the reference comes from epsilon (0.004 in the rise
# velocity from level 1 to 2), so the levels refine epsilon and keep the rest lean.
POINTS_ACROSS_INTERFACE = 2


def level_overrides(level, scene):
    """Level 0 is the demo's epsilon and dt; each level divides both by sqrt(2). The base
    mesh stays the demo's; the refinement levels follow from epsilon and
    POINTS_ACROSS_INTERFACE (numerics.mesh.points_across_interface)."""
    f = math.sqrt(2) ** level
    return {"numerics.epsilon": scene["numerics"]["epsilon"] / f,
            "numerics.dt": scene["numerics"]["dt"] / f,
            "numerics.mesh.points_across_interface": POINTS_ACROSS_INTERFACE}


def read_scene(scene):
    import yaml
    with open(scene) as f:
        return yaml.safe_load(f)


def read_columns(out):
    with open(out / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows if len(r) == len(rows[0]) and None not in r.values()]
            for k in rows[0]}


def existing(case, level):
    """A finished run from an earlier call (--report-only). Its wall time is read back
    from wall_time.txt, or else estimated as the sum of the step timings."""
    scene = ROOT / "demos" / f"rising-bubble-case{case}" / "scene.yaml"
    out = WORK / f"case{case}-level{level}"
    overrides = level_overrides(level, read_scene(scene))
    cols = read_columns(out)
    wall_file = out / "wall_time.txt"
    if wall_file.exists():
        wall = float(wall_file.read_text())
    else:
        wall = sum(sum(cols[k]) for k in cols if k.startswith("wall_") and k != "wall_flow")
    print(f"  case {case} level {level}: read back, t = {cols['time'][-1]:g}", flush=True)
    return cols, wall, overrides


def run(case, level, end_time, ranks, exe):
    scene = ROOT / "demos" / f"rising-bubble-case{case}" / "scene.yaml"
    out = WORK / f"case{case}-level{level}"
    shutil.rmtree(out, ignore_errors=True)
    overrides = level_overrides(level, read_scene(scene))
    if end_time is not None:
        overrides["numerics.end_time"] = end_time
    args = [str(exe), "run", str(scene), "--set", f"output.directory={out}",
            "--set", "output.every=0", "--set", "output.progress=false"]
    for key, value in overrides.items():
        args += ["--set", f"{key}={value}"]
    if ranks > 1:
        root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
        args = ["mpirun", *root, "-x", "OPENBLAS_NUM_THREADS=1", "-n", str(ranks)] + args
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        sys.exit(f"case {case} level {level} failed (exit {proc.returncode}):\n{proc.stderr}")
    (out / "wall_time.txt").write_text(f"{wall:.1f}\n")
    cols = read_columns(out)
    print(f"  case {case} level {level}: eps {overrides['numerics.epsilon']:.4g}, "
          f"{int(max(cols['dofs']))} dofs, {len(cols['time']) - 1} steps, {wall:.0f} s", flush=True)
    return cols, wall, overrides


def first_maximum(t, v):
    """First local maximum of v that is also the largest value within 0.2 time units on
    either side (ignores wiggles of a few time steps)."""
    for i in range(1, len(v) - 1):
        if v[i] >= v[i - 1] and v[i] > v[i + 1]:
            window = [v[j] for j in range(len(v)) if abs(t[j] - t[i]) <= 0.2]
            if v[i] >= max(window):
                return v[i], t[i]
    i = max(range(len(v)), key=v.__getitem__)
    return v[i], t[i]


def quantities(cols, case):
    t, c, u, y = cols["time"], cols["circularity"], cols["rise_velocity"], cols["center_y"]
    i = min(range(len(c)), key=c.__getitem__)
    if case == 2:
        umax, tu = first_maximum(t, u)
    else:
        j = max(range(len(u)), key=u.__getitem__)
        umax, tu = u[j], t[j]
    return {"circularity_min": c[i], "t_circularity_min": t[i], "rise_velocity_max": umax,
            "t_rise_velocity_max": tu, "y_center_final": y[-1]}


def split_of_solve_time(cols):
    """Wall time of the run by subproblem and part, as fractions of their total: the flow
    step (wall_flow), the phase-field step (the rest of assembly, factorisation and
    solve), remeshing and output."""
    steps = sum(cols["wall_assembly"]) + sum(cols["wall_factorise"]) + sum(cols["wall_solve"])
    parts = {"flow": sum(cols["wall_flow"]), "phase field": steps - sum(cols["wall_flow"]),
             "remeshing": sum(cols["wall_remesh"]), "output": sum(cols["wall_output"])}
    total = sum(parts.values()) or 1.0
    return {k: v / total for k, v in parts.items()}


def plot(case, runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ref = REFERENCE[case]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for level, (cols, _, overrides) in runs.items():
        label = f"level {level} (eps {overrides['numerics.epsilon']:.3g})"
        axes[0].plot(cols["time"], cols["circularity"], label=label)
        axes[1].plot(cols["time"], cols["rise_velocity"], label=label)
        axes[2].plot(cols["time"], cols["center_y"], label=label)
    marker = dict(color="k", marker="x", markersize=9, linestyle="none",
                  label="Hysing et al. (2009)")
    axes[0].plot(ref["t_circularity_min"][0], ref["circularity_min"][0], **marker)
    axes[1].plot(ref["t_rise_velocity_max"][0], ref["rise_velocity_max"][0], **marker)
    axes[2].plot(3.0, ref["y_center_final"][0], **marker)
    for ax, name in zip(axes, ["circularity", "rise velocity", "centre of mass y"]):
        ax.set_xlabel("time")
        ax.set_ylabel(name)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Rising bubble, test case {case}")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def report_case(case, runs):
    """Markdown lines for one case; also writes its CSV and plot."""
    ref = REFERENCE[case]
    rows = []
    for level, (cols, wall, _) in runs.items():
        q = quantities(cols, case)
        rows.append({"level": level, "dofs": int(max(cols["dofs"])), "wall_time_s": round(wall, 1),
                     **{k: round(v, 5) for k, v in q.items()}})
    with open(RESULTS / f"rising-bubble-case{case}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_COLUMNS)
        w.writeheader()
        w.writerows(rows)
    plot(case, runs, RESULTS / f"rising-bubble-case{case}.png")

    lines = [f"## Test case {case}", "",
             "| level | eps | dofs (max) | steps | wall s | " + " | ".join(QUANTITIES) + " |",
             "|---" * (5 + len(QUANTITIES)) + "|"]
    for row, (level, (cols, _, ov)) in zip(rows, runs.items()):
        lines.append(f"| {level} | {ov['numerics.epsilon']:.4g} | {row['dofs']} | "
                     f"{len(cols['time']) - 1} | {row['wall_time_s']} | "
                     + " | ".join(f"{row[k]:.4f}" for k in QUANTITIES) + " |")
    lines.append("| reference | | | | | " + " | ".join(f"{ref[k][0]:.4f}" for k in QUANTITIES) + " |")
    lines.append("| spread of the three groups | | | | | "
                 + " | ".join(f"{ref[k][1][0]:.4f}-{ref[k][1][1]:.4f}" for k in QUANTITIES) + " |")
    lines += ["", "Relative error against the reference:", "",
              "| level | " + " | ".join(QUANTITIES) + " | all within 1% |",
              "|---" * (2 + len(QUANTITIES)) + "|"]
    reached = []
    for row in rows:
        errors = [abs(row[k] - ref[k][0]) / abs(ref[k][0]) for k in QUANTITIES]
        lines.append(f"| {row['level']} | " + " | ".join(f"{e:.2%}" for e in errors)
                     + f" | {'yes' if max(errors) <= 0.01 else 'no'} |")
        if max(errors) <= 0.01:
            reached.append(row)
    if reached:
        row = reached[0]
        lines += ["", f"Level {row['level']} is the first with all five quantities within 1 %: "
                  f"{row['wall_time_s']:.0f} s ({row['wall_time_s'] / 60:.1f} min) to t = 3 on "
                  f"up to {row['dofs']} dofs, one MPI rank."]
    lines += ["", "The flow matrix depends on rho(phi) and eta(phi), so the flow is factorised "
              "every step here; reusing the factorisation applies to Stokes flow with equal "
              "viscosities and is measured by `flow_reuse.py` (`flow-reuse.md`)."]
    finest = list(runs.values())[-1][0]
    split = split_of_solve_time(finest)
    lines += ["", "Wall time of the finest level by part of the step: "
              + ", ".join(f"{k} {v:.0%}" for k, v in sorted(split.items(), key=lambda kv: -kv[1])),
              "", f"![case {case}](rising-bubble-case{case}.png)", ""]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", type=int, nargs="+", default=[1, 2], choices=[1, 2])
    parser.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--end-time", type=float, default=None,
                        help="stop earlier than t = 3 (to try the script)")
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("--exe", default=str(EXE), help="cellphase binary (default build/cellphase)")
    parser.add_argument("--report-only", action="store_true",
                        help="report the runs already in output/benchmarks/rising-bubble")
    args = parser.parse_args()
    if not Path(args.exe).exists():
        sys.exit(f"{args.exe} not found: build first (bash .ci/setup.sh)")
    WORK.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    for case in args.case:
        lines = [f"# Rising bubble, test case {case} (Hysing et al. 2009)", "",
                 f"Machine: {platform.node()}, {os.cpu_count()} cores (shared); "
                 f"{datetime.date.today()}; {args.ranks} MPI rank(s); end time "
                 f"{args.end_time or 3}. Generated by benchmarks/rising_bubble.py.", ""]
        runs = {level: existing(case, level) if args.report_only
                else run(case, level, args.end_time, args.ranks, args.exe) for level in args.levels}
        lines += report_case(case, runs)
        out = RESULTS / f"rising-bubble-case{case}.md"
        out.write_text("\n".join(lines))
        print(f"report: {out}")


if __name__ == "__main__":
    main()
