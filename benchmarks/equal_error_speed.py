#!/usr/bin/python3
"""Error against wall time for every time scheme and solver (issue: faster at equal error).

The 2D vesicle relaxation (demos/vesicle-relaxation, its mesh built once so that every run
has the same mesh and only the time discretisation differs) is run with
  - time_scheme euler (the thesis') and bdf2, linearisation taylor, at dt, dt/2, dt/4;
  - the stabilised constant-matrix linearisation (euler only) at dt .. dt/4;
  - bdf2 and euler with numerics.adaptive_dt at tolerances 1e-1 .. 1e-4 (first step 1e-5);
each with numerics.solver direct and reuse, to t = END (the relaxation, in which the
Helfrich energy falls from 10.3 to 5.93 by t = 0.1; the demo runs on to 0.24). The error is ||e||_2 of
section 5.3, the relative l2 norm over the times k dt (k = 1 .. END/dt, the rows of the thesis
scheme), of the Helfrich energy against BDF2 at dt/32; both interpolated linearly between
their rows (adaptive runs have rows elsewhere).

Writes benchmarks/results/equal-error-speed.csv with the columns
  scene,scheme,solver,dt_or_tol,wall_time_s,steps,factorisations,krylov_iterations,error
(scheme: euler, bdf2, stabilised, or adaptive-<scheme>; dt_or_tol: the step or the
tolerance), equal-error-speed.md (the fastest combination at or below the error of the
thesis scheme at the demo's dt, and its speed-up) and equal-error-speed-vesicle.png (error
against wall time, one line per combination).

Usage: /usr/bin/python3 benchmarks/equal_error_speed.py [--quick] [--keep]
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from vesicle_benchmark import interp  # noqa: E402

EXE = ROOT / "build" / "cellphase"
WORK = ROOT / "output" / "benchmarks" / "equal-error"
RESULTS = ROOT / "benchmarks" / "results"
SCENE = ROOT / "demos" / "vesicle-relaxation" / "scene.yaml"
DT = 4e-3          # the demo's (thesis-like) step
END = 0.12
KEY = "helfrich_energy"
COLUMNS = ["scene", "scheme", "solver", "dt_or_tol", "wall_time_s", "steps", "factorisations",
           "krylov_iterations", "error"]


def error_norm(reference, cols, key):
    """||e||_2 of section 5.3 at the times k DT, k = 1 .. END/DT."""
    times = [k * DT for k in range(1, round(END / DT) + 1)]
    num = den = 0.0
    for t in times:
        r = interp(t, reference["time"], reference[key])
        num += (interp(t, cols["time"], cols[key]) - r) ** 2
        den += r ** 2
    return (num / den) ** 0.5


def load(name):
    """A finished run: (columns, wall s, factorisations, Krylov iterations)."""
    out = WORK / name
    with open(out / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    cost = json.loads((out / "cost.json").read_text())
    return cols, cost["wall_time_s"], cost["factorisations"], cost["krylov_iterations"]


def run(name, overrides, keep=False):
    """Run the vesicle with overrides (with keep: load the run made before, if it finished);
    (columns, wall s, factorisations, Krylov iterations)."""
    if keep and (WORK / name / "cost.json").exists():
        return load(name)
    out = WORK / name
    shutil.rmtree(out, ignore_errors=True)
    args = [str(EXE), "run", str(SCENE), "--set", f"output.directory={out}",
            "--set", "output.every=0", "--set", "output.progress=false",
            "--set", "output.checkpoints.every=0", "--set", "numerics.mesh.remesh_every=0",
            "--set", f"numerics.end_time={END}"]
    for key, value in overrides.items():
        args += ["--set", f"{key}={value}"]
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True,
                          env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        sys.exit(f"benchmark run '{name}' failed:\n{proc.stdout}\n{proc.stderr}")
    summary = re.search(r"(\d+) factorisations(?:, (\d+) Krylov iterations)?", proc.stdout)
    (out / "cost.json").write_text(json.dumps({
        "wall_time_s": wall, "factorisations": int(summary.group(1)),
        "krylov_iterations": int(summary.group(2) or 0)}))
    cols, _, _, _ = load(name)
    print(f"  {name}: {len(cols['step']) - 1} steps, {wall:.1f} s", flush=True)
    return load(name)


def combinations(quick):
    """(scheme label, solver, dt_or_tol, overrides) of every member."""
    steps = (1, 2) if quick else (1, 2, 4)
    tolerances = (1e-1, 1e-2) if quick else (1e-1, 1e-2, 1e-3, 1e-4)
    for solver in ("direct", "reuse"):
        for k in steps:
            for scheme in ("euler", "bdf2"):
                yield scheme, solver, DT / k, {"numerics.dt": DT / k,
                                               "numerics.time_scheme": scheme,
                                               "numerics.solver": solver}
            yield "stabilised", solver, DT / k, {"numerics.dt": DT / k,
                                                 "numerics.linearisation": "stabilised",
                                                 "numerics.solver": solver}
        for tol in tolerances:
            for scheme in ("bdf2", "euler"):
                yield f"adaptive-{scheme}", solver, tol, {
                    "numerics.dt": 1e-5, "numerics.time_scheme": scheme,
                    "numerics.solver": solver, "numerics.adaptive_dt": f"{{tolerance: {tol}}}"}


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
    groups = sorted({(r["scheme"], r["solver"]) for r in rows})
    for scheme, solver in groups:
        mine = sorted((r for r in rows if (r["scheme"], r["solver"]) == (scheme, solver)),
                      key=lambda r: r["wall_time_s"])
        ax.loglog([r["wall_time_s"] for r in mine], [r["error"] for r in mine],
                  "o-" if solver == "direct" else "s--", label=f"{scheme}, {solver}")
    thesis = next(r for r in rows if r["scheme"] == "euler" and r["solver"] == "direct"
                  and abs(r["dt_or_tol"] - DT) < 1e-15)
    ax.axhline(thesis["error"], color="grey", lw=0.8)
    ax.annotate("thesis scheme at the demo's dt", (thesis["wall_time_s"], thesis["error"]),
                textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel(f"||e||_2 of {KEY} (section 5.3)")
    ax.set_title("Vesicle relaxation: error against cost", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    fig.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer members (a smoke run)")
    parser.add_argument("--keep", action="store_true",
                        help="do not run again the runs that finished before "
                             "(output/benchmarks/equal-error): the report from them, and the "
                             "missing ones run")
    a = parser.parse_args()
    print(f"vesicle: reference BDF2 at dt/32 = {DT / 32:g}", flush=True)
    reference, _, _, _ = run("reference", {"numerics.dt": DT / 32, "numerics.time_scheme": "bdf2"},
                             a.keep)
    rows = []
    for scheme, solver, value, overrides in combinations(a.quick):
        cols, wall, factorisations, iterations = run(f"{scheme}-{solver}-{value:g}", overrides,
                                                     a.keep)
        rows.append({"scene": "vesicle-relaxation", "scheme": scheme, "solver": solver,
                     "dt_or_tol": value, "wall_time_s": wall, "steps": len(cols["step"]) - 1,
                     "factorisations": factorisations, "krylov_iterations": iterations,
                     "error": error_norm(reference, cols, KEY)})
    RESULTS.mkdir(parents=True, exist_ok=True)
    with open(RESULTS / "equal-error-speed.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({**r, "wall_time_s": f"{r['wall_time_s']:.2f}", "error": f"{r['error']:.3e}",
                        "dt_or_tol": f"{r['dt_or_tol']:g}"})
    plot(rows, RESULTS / "equal-error-speed-vesicle.png")

    thesis = next(r for r in rows if r["scheme"] == "euler" and r["solver"] == "direct"
                  and abs(r["dt_or_tol"] - DT) < 1e-15)
    good = [r for r in rows if r["error"] <= thesis["error"]]
    best = min(good, key=lambda r: r["wall_time_s"])
    lines = ["# Error against wall time: time schemes and solvers", "",
             f"Machine: {platform.node()}, {os.cpu_count()} cores (shared); "
             f"{datetime.date.today()}. Generated by benchmarks/equal_error_speed.py"
             f"{' --quick' if a.quick else ''} (one rank, OPENBLAS_NUM_THREADS=1, one run "
             "each: wall times carry the machine's noise of some 10 %).", "",
             "Vesicle relaxation (demos/vesicle-relaxation, mesh built once, "
             f"{int(reference['dofs'][-1])} dofs, t = {END:g}). Error: ||e||_2 of the Helfrich "
             f"energy (section 5.3) against BDF2 at dt = {DT / 32:g}.", "",
             "| scheme | solver | dt or tolerance | wall s | steps | factorisations | "
             "Krylov iterations | error |", "|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: r["error"]):
        lines.append(f"| {r['scheme']} | {r['solver']} | {r['dt_or_tol']:g} | "
                     f"{r['wall_time_s']:.1f} | {r['steps']} | {r['factorisations']} | "
                     f"{r['krylov_iterations']} | {r['error']:.2e} |")
    # The thesis scheme's cost at a smaller error: its ladder (euler, direct, dt .. dt/4)
    # fitted as wall = c error^-q in log-log and extrapolated (marked as such).
    ladder = sorted((r for r in rows if r["scheme"] == "euler" and r["solver"] == "direct"),
                    key=lambda r: r["error"])
    xs = [math.log(r["error"]) for r in ladder]
    ys = [math.log(r["wall_time_s"]) for r in ladder]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)

    def thesis_time(error):
        return math.exp(my + slope * (math.log(error) - mx))
    lines += ["", "Each combination against the thesis scheme at the same error: the thesis "
              f"ladder's wall time fitted as wall ~ error^{slope:.2f} (from {len(ladder)} "
              f"points, errors {ladder[0]['error']:.2e} .. {ladder[-1]['error']:.2e}; beyond "
              "them extrapolated):", "",
              "| scheme | solver | dt or tolerance | error | wall s | thesis scheme at that error s "
              "| speed-up |", "|---|---|---|---|---|---|---|"]
    for r in sorted(good, key=lambda r: thesis_time(r["error"]) / r["wall_time_s"], reverse=True):
        t = thesis_time(r["error"])
        extrapolated = r["error"] < ladder[0]["error"]
        lines.append(f"| {r['scheme']} | {r['solver']} | {r['dt_or_tol']:g} | {r['error']:.2e} | "
                     f"{r['wall_time_s']:.1f} | {t:.0f}{' (extrapolated)' if extrapolated else ''} "
                     f"| {t / r['wall_time_s']:.1f}x |")
    lines += ["", f"The thesis scheme (euler, direct, dt = {DT:g}) has error "
              f"{thesis['error']:.2e} in {thesis['wall_time_s']:.1f} s. The fastest combination "
              f"at or below that error: {best['scheme']}, {best['solver']}, "
              f"{best['dt_or_tol']:g}: {best['wall_time_s']:.1f} s, error {best['error']:.2e}, "
              f"{thesis['wall_time_s'] / best['wall_time_s']:.2f}x faster."]
    (RESULTS / "equal-error-speed.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines[-1:]))


if __name__ == "__main__":
    main()
