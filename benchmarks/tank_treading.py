#!/usr/bin/python3
"""Tank-treading vesicle with an inextensible membrane: steady angle against reduced area.

Steady inclination angle of a vesicle in simple shear against reduced area and mesh level.

Runs demos/vesicle-tank-treading/scene.yaml (2D, Stokes, viscosity ratio 1, local
inextensibility (3.67)-(3.68) with xi = 1 and the global area constraint (3.69)) for the
reduced areas nu = 4 pi A / L^2 given by --areas. Each vesicle starts as an ellipse at 45
degrees with a b = 0.15 (the enclosed area of demos/vesicle-shear); the semi-axes for nu
come from the ellipse perimeter, computed numerically (trapezoidal rule, which converges
exponentially for the periodic integrand), and go to the run as --set cells.0.semi_axes.
Level l divides epsilon and dt by sqrt(2)^l and multiplies the base cells per axis by
sqrt(2)^l, as benchmarks/rising_bubble.py does (level 0 is the demo).

The steady inclination angle is the mean of inclination_deg over the last 10 % of the run
time; the report also gives the change of the angle over the last 0.5 time units, to show
whether it has settled. length_drift_rel is max over time of |L(t) - L(0)| / L(0) with L the
membrane length (column `surface`).

Writes
  benchmarks/results/tank-treading.csv   one row per run (angle in radians)
  benchmarks/results/tank-treading.md    machine, date, table, change between levels
  benchmarks/results/tank-treading.png   angle against reduced area per level; angle over time
Runs go to output/benchmarks/tank-treading/nu<nu>-level<l>/.

Usage: /usr/bin/python3 benchmarks/tank_treading.py [--areas 0.7 0.8 0.9] [--levels 0 1]
                     [--end-time T] [--exe PATH] [--report-only]
With --report-only the runs of the given areas and levels that are already in the work
directory are read back (missing ones are listed and left out), nothing is run.
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
SCENE = ROOT / "demos" / "vesicle-tank-treading" / "scene.yaml"
WORK = ROOT / "output" / "benchmarks" / "tank-treading"
RESULTS = ROOT / "benchmarks" / "results"
AREA_PRODUCT = 0.15          # a b of the initial ellipse (area pi a b, as vesicle-shear)
STEADY_FRACTION = 0.1        # the steady angle is the mean over the last 10 % of the run
SETTLE_WINDOW = 0.5          # change of the angle over the last 0.5 time units
CSV_COLUMNS = ["reduced_area", "level", "epsilon", "dofs", "wall_time_s",
               "inclination_angle_rad", "length_drift_rel"]


def ellipse_perimeter(a, b, n=4096):
    """Perimeter of the ellipse with semi-axes a, b by the trapezoidal rule in the angle
    (exponentially accurate for this smooth periodic integrand)."""
    h = 2 * math.pi / n
    return h * sum(math.hypot(a * math.sin(k * h), b * math.cos(k * h)) for k in range(n))


def semi_axes(nu):
    """Semi-axes (a, b), a >= b, of the ellipse with a b = AREA_PRODUCT and reduced area
    4 pi A / L^2 = nu, by bisection on the aspect ratio a / b."""
    if not 0 < nu < 1:
        sys.exit(f"reduced area {nu} must lie in (0, 1)")
    area = math.pi * AREA_PRODUCT

    def axes(r):
        b = math.sqrt(AREA_PRODUCT / r)
        return AREA_PRODUCT / b, b

    lo, hi = 1.0, 100.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        a, b = axes(mid)
        if 4 * math.pi * area / ellipse_perimeter(a, b) ** 2 > nu:
            lo = mid
        else:
            hi = mid
    return axes(0.5 * (lo + hi))


def read_scene():
    import yaml
    with open(SCENE) as f:
        return yaml.safe_load(f)


def overrides_for(nu, level, end_time):
    scene = read_scene()
    f = math.sqrt(2) ** level
    nx, ny = scene["domain"]["resolution"][:2]
    a, b = semi_axes(nu)
    ov = {"cells.0.semi_axes": f"[{a:.6f},{b:.6f}]",
          "numerics.epsilon": scene["numerics"]["epsilon"] / f,
          "numerics.dt": scene["numerics"]["dt"] / f,
          "domain.resolution": f"[{round(nx * f)},{round(ny * f)}]"}
    if end_time is not None:
        ov["numerics.end_time"] = end_time
    return ov


def run_dir(nu, level):
    return WORK / f"nu{nu:g}-level{level}"


def read_columns(out):
    with open(out / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows if len(r) == len(rows[0]) and None not in r.values()]
            for k in rows[0]}


def existing(nu, level, end_time):
    out = run_dir(nu, level)
    if not (out / "observables.csv").exists() or not (out / "wall_time.txt").exists():
        print(f"  nu {nu:g} level {level}: no finished run in {out}, left out", flush=True)
        return None
    cols = read_columns(out)
    wall = float((out / "wall_time.txt").read_text())
    print(f"  nu {nu:g} level {level}: read back, t = {cols['time'][-1]:g}", flush=True)
    return cols, wall, overrides_for(nu, level, end_time)


def run(nu, level, end_time, exe):
    out = run_dir(nu, level)
    shutil.rmtree(out, ignore_errors=True)
    ov = overrides_for(nu, level, end_time)
    args = [str(exe), "run", str(SCENE), "--set", f"output.directory={out}",
            "--set", "output.every=0", "--set", "output.progress=false"]
    for key, value in ov.items():
        args += ["--set", f"{key}={value}"]
    print(f"  nu {nu:g} level {level}: {' '.join(args)}", flush=True)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    (out / "stdout.txt").write_text(proc.stdout)
    (out / "stderr.txt").write_text(proc.stderr)
    if proc.returncode != 0:
        print(f"  nu {nu:g} level {level} FAILED (exit {proc.returncode}) after {wall:.0f} s:\n"
              f"{proc.stderr}", flush=True)
        return None
    (out / "wall_time.txt").write_text(f"{wall:.1f}\n")
    cols = read_columns(out)
    print(f"  nu {nu:g} level {level}: eps {ov['numerics.epsilon']:.4g}, "
          f"{int(max(cols['dofs']))} dofs, {len(cols['time']) - 1} steps, {wall:.0f} s",
          flush=True)
    return cols, wall, ov


def value_at(t, y, when):
    """y at the last sample with t <= when."""
    i = max(j for j in range(len(t)) if t[j] <= when + 1e-12)
    return y[i]


def quantities(cols):
    t, ang, length = cols["time"], cols["inclination_deg"], cols["surface"]
    t_end = t[-1]
    window = [a for s, a in zip(t, ang) if s >= (1 - STEADY_FRACTION) * t_end - 1e-12]
    steady = sum(window) / len(window)
    settle = ang[-1] - value_at(t, ang, t_end - SETTLE_WINDOW)
    drifts = [abs(s - length[0]) / length[0] for s in length]
    i_drift = max(range(len(drifts)), key=drifts.__getitem__)
    drift = drifts[i_drift]
    return {"angle_deg": steady, "angle_rad": math.radians(steady), "settle_deg": settle,
            "length_drift": drift, "t_length_drift": t[i_drift],
            "length_drift_late": max(d for s, d in zip(t, drifts) if s >= 1), "finite": all(math.isfinite(a) for a in ang),
            "t_end": t_end, "volume_drift": max(abs(v - cols["volume"][0]) for v in cols["volume"])
            / cols["volume"][0],
            "stretch_min": min(cols["stretch_min"]), "stretch_max": max(cols["stretch_max"]),
            "tension_end": cols["tension_mean"][-1]}


def plot(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
    levels = sorted({level for _, level in runs})
    for level in levels:
        pts = sorted((nu, quantities(r[0])["angle_deg"]) for (nu, l), r in runs.items()
                     if l == level)
        eps = next(r[2]["numerics.epsilon"] for (nu, l), r in runs.items() if l == level)
        axes[0].plot([p[0] for p in pts], [p[1] for p in pts], marker="o",
                     label=f"level {level} (eps {eps:.3g})")
    axes[0].set_xlabel("reduced area 4 pi A / L^2")
    axes[0].set_ylabel("steady inclination angle (deg)")
    axes[0].legend(fontsize=8)
    styles = ["-", "--", ":", "-."]
    for (nu, level), (cols, _, _) in sorted(runs.items()):
        color = {0.7: "C0", 0.8: "C1", 0.9: "C2"}.get(round(nu, 3), None)
        axes[1].plot(cols["time"], cols["inclination_deg"], styles[level % len(styles)],
                     color=color, label=f"nu {nu:g}, level {level}")
    axes[1].set_xlabel("time (shear rate 1)")
    axes[1].set_ylabel("inclination (deg)")
    axes[1].legend(fontsize=7, ncol=2)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.suptitle("Tank-treading vesicle, inextensible membrane (xi = 1, global area)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def report(runs, failed, end_time):
    rows = []
    for (nu, level), (cols, wall, ov) in sorted(runs.items()):
        q = quantities(cols)
        rows.append({"reduced_area": nu, "level": level,
                     "epsilon": round(ov["numerics.epsilon"], 6),
                     "dofs": int(max(cols["dofs"])), "wall_time_s": round(wall, 1),
                     "inclination_angle_rad": round(q["angle_rad"], 6),
                     "length_drift_rel": f"{q['length_drift']:.4e}"})
    with open(RESULTS / "tank-treading.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_COLUMNS)
        w.writeheader()
        w.writerows(rows)
    plot(runs, RESULTS / "tank-treading.png")

    lines = ["# Tank-treading vesicle with an inextensible membrane", "",
             f"Machine: {platform.node()}, {os.cpu_count()} cores (shared with other jobs); "
             f"{datetime.date.today()}; 1 MPI rank, OPENBLAS_NUM_THREADS=1. "
             "Generated by benchmarks/tank_treading.py.", "",
             "Scene: demos/vesicle-tank-treading/scene.yaml (2D, Stokes, viscosity ratio 1, "
             "shear rate 1 between walls at y = -1, 1, periodic in x, Be = 10, inextensibility "
             "xi = 1 with the global area constraint). Initial ellipse at 45 deg with a b = "
             f"{AREA_PRODUCT}; end time {end_time if end_time is not None else read_scene()['numerics']['end_time']:g}. "
             "Level l: epsilon and dt divided by sqrt(2)^l, base cells per axis multiplied by "
             "sqrt(2)^l.", "",
             f"Steady angle: mean of `inclination_deg` over the last {STEADY_FRACTION:.0%} of "
             f"the run time. `change last {SETTLE_WINDOW:g}`: angle at the end minus the angle "
             f"{SETTLE_WINDOW:g} time units before (settled if small). Length drift: max over "
             "time of |L(t) - L(0)| / L(0), L the membrane length, with the time where it "
             "occurs, and the same maximum over t >= 1 only. Volume drift likewise. Stretch: "
             "the smallest `stretch_min` and largest `stretch_max` of the run.", "",
             "| reduced area | semi-axes | level | eps | dofs (max) | steps | wall s | "
             f"angle deg | angle rad | change last {SETTLE_WINDOW:g} (deg) | length drift (when) | "
             "length drift t >= 1 | "
             "volume drift | stretch min / max | tension_mean (end) |",
             "|---" * 15 + "|"]
    for (nu, level), (cols, wall, ov) in sorted(runs.items()):
        q = quantities(cols)
        flag = "" if q["finite"] else " (NaN/Inf in the angle)"
        lines.append(
            f"| {nu:g} | {ov['cells.0.semi_axes']} | {level} | {ov['numerics.epsilon']:.4g} | "
            f"{int(max(cols['dofs']))} | {len(cols['time']) - 1} | {wall:.0f} | "
            f"{q['angle_deg']:.2f}{flag} | {q['angle_rad']:.4f} | {q['settle_deg']:+.3f} | "
            f"{q['length_drift']:.2%} (t = {q['t_length_drift']:g}) | {q['length_drift_late']:.3%} | "
            f"{q['volume_drift']:.1e} | "
            f"{q['stretch_min']:.3f} / {q['stretch_max']:.3f} | {q['tension_end']:.3g} |")
    changes = []
    for (nu, level), (cols, _, _) in sorted(runs.items()):
        if (nu, level - 1) in runs:
            a0 = quantities(runs[(nu, level - 1)][0])["angle_deg"]
            a1 = quantities(cols)["angle_deg"]
            changes.append(f"| {nu:g} | {level - 1} -> {level} | {a1 - a0:+.3f} | "
                           f"{abs(a1 - a0) / abs(a0):.2%} |")
    if changes:
        lines += ["", "Change of the steady angle between levels:", "",
                  "| reduced area | levels | change (deg) | relative |", "|---|---|---|---|"]
        lines += changes
    if failed:
        lines += ["", "Runs that failed or are missing: "
                  + ", ".join(f"nu {nu:g} level {level}" for nu, level in failed) + "."]
    lines += ["", "![tank-treading](tank-treading.png)", ""]
    out = RESULTS / "tank-treading.md"
    out.write_text("\n".join(lines))
    print("\n".join(lines))
    print(f"report: {out}")


def main():
    global EXE
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--areas", type=float, nargs="+", default=[0.7, 0.8, 0.9],
                        help="reduced areas 4 pi A / L^2 in (0, 1)")
    parser.add_argument("--levels", type=int, nargs="+", default=[0, 1],
                        help="mesh levels (epsilon, dt / sqrt(2)^l, base cells * sqrt(2)^l)")
    parser.add_argument("--end-time", type=float, default=None,
                        help="end time instead of the scene's (to try the script)")
    parser.add_argument("--exe", type=Path, default=EXE, help="cellphase binary")
    parser.add_argument("--report-only", action="store_true",
                        help="report the runs already in output/benchmarks/tank-treading")
    args = parser.parse_args()
    if not args.report_only and not args.exe.exists():
        sys.exit(f"{args.exe} not found: build first (bash .ci/setup.sh) or give --exe")
    WORK.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    runs, failed = {}, []
    for level in args.levels:
        for nu in args.areas:
            r = (existing(nu, level, args.end_time) if args.report_only
                 else run(nu, level, args.end_time, args.exe))
            if r is None:
                failed.append((nu, level))
            else:
                runs[(nu, level)] = r
    if not runs:
        sys.exit("no finished runs to report")
    report(runs, failed, args.end_time)


if __name__ == "__main__":
    main()
