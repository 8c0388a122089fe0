#!/usr/bin/python3
"""Error against wall time for every time scheme and solver (issue: faster at equal error).

Three scenes, each against a small-step BDF2 reference of its own:
  - vesicle: the 2D vesicle relaxation (demos/vesicle-relaxation), its mesh built once so
    that only the time discretisation differs, to t = 0.12 (the Helfrich energy falls from
    10.3 to 5.93 by t = 0.1); error of the Helfrich energy; reference at dt/32;
  - bubble: the rising bubble, case 1 at level 2 of benchmarks/rising_bubble.py (eps 0.01,
    dt 2.5e-3, 2 points across the interface), Navier-Stokes-Cahn-Hilliard, to t = 1 (the
    rise velocity peaks at 0.92); remeshing every 4 steps of the demo's dt, i.e. at the same
    times in every run with a fixed step; error of the rise velocity; reference at dt/16;
  - shear: the inextensible vesicle in shear (demos/vesicle-shear with the local constraint
    xi = 1, section 3.4.3), Stokes-Helfrich (H^-1 flow), to t = 0.5; remeshing every 5 steps
    of the demo's dt; error of the inclination angle; reference at dt/32.
Members: time_scheme euler (the thesis') and bdf2, linearisation taylor, at a ladder of steps
around the demo's dt; the stabilised constant-matrix linearisation (vesicle); euler and bdf2
with numerics.adaptive_dt at several tolerances; numerics.solver direct, and reuse where the
scene has it in its list (vesicle and shear). The error is ||e||_2 of section 5.3, the
relative l2 norm over the times k dt (k = 1 .. END/dt, dt the demo's: the rows of the thesis
scheme) of the scene's observable against the reference, both interpolated linearly between
their rows (adaptive runs have rows elsewhere).

Writes benchmarks/results/equal-error-speed.csv with the columns
  scene,scheme,solver,dt_or_tol,wall_time_s,steps,factorisations,krylov_iterations,error
(scheme: euler, bdf2, stabilised, or adaptive-<scheme>; dt_or_tol: the step or the
tolerance), equal-error-speed.md (per scene: every member, and each against the thesis
scheme at the same error) and equal-error-speed-<scene>.png (error against wall time, one
line per combination).

Usage: /usr/bin/python3 benchmarks/equal_error_speed.py [--scenes vesicle bubble shear]
       [--quick] [--keep]
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

# $CELLPHASE_EXE runs a copy, so that a rebuild cannot replace the binary under a running study
EXE = Path(os.environ.get("CELLPHASE_EXE", ROOT / "build" / "cellphase"))
WORK = ROOT / "output" / "benchmarks" / "equal-error"
RESULTS = ROOT / "benchmarks" / "results"
TARGET = 5  # the speed-up asked for at the thesis scheme's error
COLUMNS = ["scene", "scheme", "solver", "dt_or_tol", "wall_time_s", "steps", "factorisations",
           "krylov_iterations", "error"]

# name: the demo scene, its (thesis-like) dt, the end time, the observable, the reference's
# step divisor, the overrides of every run, the remesh interval in steps of dt (0: the mesh
# built once), the step ladder (multiples of dt), tolerances, first adaptive step, solvers,
# and whether the stabilised linearisation is a member; bdf2_ladder: larger steps tried with
# BDF2 only (a run that fails there, unstable or refused, is reported and left out).
SCENES = {
    "vesicle": {"title": "Vesicle relaxation", "name": "vesicle-relaxation",
                "scene": "demos/vesicle-relaxation/scene.yaml", "dt": 4e-3, "end": 0.12,
                "key": "helfrich_energy", "reference": 32, "set": {}, "remesh": 0,
                "ladder": (1, 1 / 2, 1 / 4), "tolerances": (1e-1, 1e-2, 1e-3, 1e-4),
                "first_dt": 1e-5, "solvers": ("direct", "reuse"), "stabilised": True},
    "bubble": {"title": "Rising bubble, case 1, level 2", "name": "rising-bubble-case1",
               "scene": "demos/rising-bubble-case1/scene.yaml", "dt": 2.5e-3, "end": 1.0,
               "key": "rise_velocity", "reference": 16,
               "set": {"numerics.epsilon": 0.01,
                       "numerics.mesh.points_across_interface": 2},
               "remesh": 4, "ladder": (2, 1, 1 / 2), "bdf2_ladder": (8, 4),
               "tolerances": (3e-2, 1e-2, 1e-3),
               "first_dt": 2.5e-5, "solvers": ("direct",), "stabilised": False},
    "shear": {"title": "Inextensible vesicle in shear", "name": "vesicle-shear-inextensible",
              "scene": "demos/vesicle-shear/scene.yaml", "dt": 5e-3, "end": 0.5,
              "key": "inclination_deg", "reference": 32,
              "set": {"flow.inextensibility": "{xi: 1}"},
              "remesh": 5, "ladder": (2, 1, 1 / 2), "bdf2_ladder": (8, 4),
              "tolerances": (1e-2, 3e-3, 1e-3, 1e-4),
              "first_dt": 5e-5, "solvers": ("direct", "reuse"), "stabilised": False},
}


def error_norm(case, reference, cols):
    """||e||_2 of section 5.3 at the times k dt, k = 1 .. END/dt."""
    key, dt = case["key"], case["dt"]
    times = [k * dt for k in range(1, round(case["end"] / dt) + 1)]
    num = den = 0.0
    for t in times:
        r = interp(t, reference["time"], reference[key])
        num += (interp(t, cols["time"], cols[key]) - r) ** 2
        den += r ** 2
    return (num / den) ** 0.5


def load(out):
    """A finished run: (columns, wall s, factorisations, Krylov iterations)."""
    with open(out / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    cost = json.loads((out / "cost.json").read_text())
    return cols, cost["wall_time_s"], cost["factorisations"], cost["krylov_iterations"]


def remesh_every(case, overrides):
    """The scene's remesh interval in steps: the same times for every fixed step (an
    interval of case["remesh"] steps of dt), case["remesh"] steps with adaptive steps."""
    if case["remesh"] == 0:
        return 0
    if "numerics.adaptive_dt" in overrides:
        return case["remesh"]
    return max(1, round(case["remesh"] * case["dt"] / overrides["numerics.dt"]))


def run(case, name, overrides, keep=False, may_fail=False):
    """Run the scene with overrides (with keep: load the run made before, if it finished);
    (columns, wall s, factorisations, Krylov iterations), or None if it failed and may_fail."""
    out = WORK / case["name"] / name
    if keep and (out / "cost.json").exists():
        return load(out)
    shutil.rmtree(out, ignore_errors=True)
    settings = {"output.directory": out, "output.every": 0, "output.progress": "false",
                "output.checkpoints.every": 0,
                "numerics.mesh.remesh_every": remesh_every(case, overrides),
                "numerics.end_time": case["end"], **case["set"], **overrides}
    args = [str(EXE), "run", str(ROOT / case["scene"])]
    for key, value in settings.items():
        args += ["--set", f"{key}={value}"]
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True,
                          env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        if may_fail:
            print(f"  {case['name']}/{name}: failed, left out: "
                  f"{(proc.stderr.strip().splitlines() or ['?'])[-1]}", flush=True)
            return None
        sys.exit(f"benchmark run '{case['name']}/{name}' failed:\n{proc.stdout}\n{proc.stderr}")
    summary = re.search(r"(\d+) factorisations(?:, (\d+) Krylov iterations)?", proc.stdout)
    (out / "cost.json").write_text(json.dumps({
        "wall_time_s": wall, "factorisations": int(summary.group(1)),
        "krylov_iterations": int(summary.group(2) or 0)}))
    cols, _, _, _ = load(out)
    print(f"  {case['name']}/{name}: {len(cols['step']) - 1} steps, {wall:.1f} s", flush=True)
    return load(out)


def combinations(case, quick):
    """(scheme label, solver, dt_or_tol, overrides, may fail) of every member."""
    ladder = case["ladder"][:2] if quick else case["ladder"]
    tolerances = case["tolerances"][:2] if quick else case["tolerances"]
    schemes = ("euler", "bdf2", "stabilised") if case["stabilised"] else ("euler", "bdf2")
    for solver in case["solvers"]:
        for k in ladder:
            dt = case["dt"] * k
            for scheme in schemes:
                scheme_keys = ({"numerics.linearisation": "stabilised"} if scheme == "stabilised"
                               else {"numerics.time_scheme": scheme})
                yield scheme, solver, dt, {"numerics.dt": dt, "numerics.solver": solver,
                                           **scheme_keys}, False
        for k in () if quick else case.get("bdf2_ladder", ()):
            yield "bdf2", solver, case["dt"] * k, {
                "numerics.dt": case["dt"] * k, "numerics.solver": solver,
                "numerics.time_scheme": "bdf2"}, True
        for tol in tolerances:
            for scheme in ("bdf2", "euler"):
                yield f"adaptive-{scheme}", solver, tol, {
                    "numerics.dt": case["first_dt"], "numerics.time_scheme": scheme,
                    "numerics.solver": solver, "numerics.adaptive_dt": f"{{tolerance: {tol}}}"}, False


def thesis_row(case, rows):
    """The thesis scheme at the demo's dt: euler, direct."""
    return next(r for r in rows if r["scheme"] == "euler" and r["solver"] == "direct"
                and abs(r["dt_or_tol"] - case["dt"]) < 1e-15)


def plot(case, rows, path):
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
    thesis = thesis_row(case, rows)
    ax.axhline(thesis["error"], color="grey", lw=0.8)
    ax.annotate("thesis scheme at the demo's dt", (thesis["wall_time_s"], thesis["error"]),
                textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel(f"||e||_2 of {case['key']} (section 5.3)")
    ax.set_title(f"{case['title']}: error against cost", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def report(case, rows, reference):
    """The scene's section of equal-error-speed.md."""
    thesis = thesis_row(case, rows)
    good = [r for r in rows if r["error"] <= thesis["error"]]
    best = min(good, key=lambda r: r["wall_time_s"])
    lines = [f"## {case['title']}", "",
             f"{case['scene']} with {case['set'] or 'the demo settings'}, "
             + (f"remeshed every {case['remesh']} steps of dt = {case['dt']:g} (the same times for every "
                "fixed step)" if case["remesh"] else "mesh built once")
             + f", {int(max(reference['dofs']))} dofs at most, t = {case['end']:g}. Error: ||e||_2 of "
             f"{case['key']} (section 5.3) at the times k dt against BDF2 at dt = "
             f"{case['dt'] / case['reference']:g}.", "",
             f"![error against wall time](equal-error-speed-{case_short(case)}.png)", "",
             "| scheme | solver | dt or tolerance | wall s | steps | factorisations | "
             "Krylov iterations | error |", "|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: r["error"]):
        lines.append(f"| {r['scheme']} | {r['solver']} | {r['dt_or_tol']:g} | "
                     f"{r['wall_time_s']:.1f} | {r['steps']} | {r['factorisations']} | "
                     f"{r['krylov_iterations']} | {r['error']:.2e} |")
    # The thesis scheme's cost at a smaller error: its ladder (euler, direct) fitted as
    # wall = c error^-q in log-log and extrapolated (marked as such).
    ladder = sorted((r for r in rows if r["scheme"] == "euler" and r["solver"] == "direct"),
                    key=lambda r: r["error"])
    xs = [math.log(r["error"]) for r in ladder]
    ys = [math.log(r["wall_time_s"]) for r in ladder]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)

    def thesis_time(error):
        return math.exp(my + slope * (math.log(error) - mx))
    lines += ["", "Each combination at or below the thesis scheme's error against the thesis scheme "
              f"at the same error: the thesis ladder's wall time fitted as wall ~ error^{slope:.2f} "
              f"(from {len(ladder)} points, errors {ladder[0]['error']:.2e} .. "
              f"{ladder[-1]['error']:.2e}; beyond them extrapolated):", "",
              "| scheme | solver | dt or tolerance | error | wall s | thesis scheme at that error s "
              "| speed-up |", "|---|---|---|---|---|---|---|"]
    for r in sorted(good, key=lambda r: thesis_time(r["error"]) / r["wall_time_s"], reverse=True):
        t = thesis_time(r["error"])
        extrapolated = r["error"] < ladder[0]["error"]
        lines.append(f"| {r['scheme']} | {r['solver']} | {r['dt_or_tol']:g} | {r['error']:.2e} | "
                     f"{r['wall_time_s']:.1f} | {t:.0f}{' (extrapolated)' if extrapolated else ''} "
                     f"| {t / r['wall_time_s']:.1f}x |")
    lines += ["", f"The thesis scheme (euler, direct, dt = {case['dt']:g}) has error "
              f"{thesis['error']:.2e} in {thesis['wall_time_s']:.1f} s. The fastest combination "
              f"at or below that error: {best['scheme']}, {best['solver']}, "
              f"{best['dt_or_tol']:g}: {best['wall_time_s']:.1f} s, error {best['error']:.2e}, "
              f"{thesis['wall_time_s'] / best['wall_time_s']:.2f}x faster.", ""]
    return lines


def case_short(case):
    return next(k for k, c in SCENES.items() if c is case)


def measure(case, quick, keep):
    print(f"{case['name']}: reference BDF2 at dt/{case['reference']}", flush=True)
    reference, _, _, _ = run(case, "reference",
                             {"numerics.dt": case["dt"] / case["reference"],
                              "numerics.time_scheme": "bdf2"}, keep)
    rows = []
    for scheme, solver, value, overrides, may_fail in combinations(case, quick):
        result = run(case, f"{scheme}-{solver}-{value:g}", overrides, keep, may_fail)
        if result is None:
            continue
        cols, wall, factorisations, iterations = result
        rows.append({"scene": case["name"], "scheme": scheme, "solver": solver,
                     "dt_or_tol": value, "wall_time_s": wall, "steps": len(cols["step"]) - 1,
                     "factorisations": factorisations, "krylov_iterations": iterations,
                     "error": error_norm(case, reference, cols)})
    return reference, rows


def kept_results(skip_titles, skip_names):
    """The committed summary rows, sections and csv rows of the scenes not run now (a run of
    some scenes keeps the others' results; their machine and date are those of their run)."""
    summary, sections, rows = [], [], []
    md, table = RESULTS / "equal-error-speed.md", RESULTS / "equal-error-speed.csv"
    if not md.exists() or not table.exists():
        return summary, sections, rows
    text = md.read_text()
    titles = [c["title"] for c in SCENES.values() if c["title"] not in skip_titles]
    for line in text.splitlines():
        if any(line.startswith(f"| {t} |") for t in titles):
            summary.append(line)
    parts = text.split("\n## ")
    for part in parts[1:]:
        title = part.split("\n", 1)[0].strip()
        if title in titles:
            sections += f"## {part.rstrip()}\n".splitlines() + [""]
    with open(table) as f:
        rows = [r for r in csv.DictReader(f) if r["scene"] not in skip_names]
    return summary, sections, rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="+", choices=list(SCENES), default=list(SCENES),
                        help="scenes to measure (default: all)")
    parser.add_argument("--quick", action="store_true", help="fewer members (a smoke run)")
    parser.add_argument("--keep", action="store_true",
                        help="do not run again the runs that finished before "
                             "(output/benchmarks/equal-error/<scene>): the report from them, "
                             "and the missing ones run")
    a = parser.parse_args()
    lines = ["# Error against wall time: time schemes and solvers", "",
             f"Machine: {platform.node()}, {os.cpu_count()} cores (shared); "
             f"{datetime.date.today()}. Generated by benchmarks/equal_error_speed.py"
             f"{' --quick' if a.quick else ''} (one rank, OPENBLAS_NUM_THREADS=1, one run "
             "each: wall times carry the machine's noise of some 10 %).", ""]
    all_rows, sections, summary = [], [], []
    for short in a.scenes:
        case = SCENES[short]
        reference, rows = measure(case, a.quick, a.keep)
        plot(case, rows, RESULTS / f"equal-error-speed-{short}.png")
        sections += report(case, rows, reference)
        all_rows += rows
        print(sections[-2], flush=True)
        thesis = thesis_row(case, rows)
        best = min((r for r in rows if r["error"] <= thesis["error"]),
                   key=lambda r: r["wall_time_s"])
        speed_up = thesis["wall_time_s"] / best["wall_time_s"]
        summary.append(f"| {case['title']} | {thesis['error']:.2e} | {thesis['wall_time_s']:.1f} | "
                       f"{best['scheme']}, {best['solver']}, {best['dt_or_tol']:g} | "
                       f"{best['error']:.2e} | {best['wall_time_s']:.1f} | {speed_up:.2f}x | "
                       f"{'yes' if speed_up >= TARGET else 'no'} |")
    partial = set(a.scenes) != set(SCENES)
    if partial:
        kept_summary, kept_sections, kept_rows = kept_results(
            {SCENES[k]["title"] for k in a.scenes}, {SCENES[k]["name"] for k in a.scenes})
        summary += kept_summary
        sections += kept_sections
        lines[2] += (f" Scenes {', '.join(a.scenes)} measured on this date; the others' rows "
                     "are kept from their own earlier run.")
    lines += ["Target: at the error of the thesis scheme (euler, taylor, direct, fixed step) at the "
              f"demo's dt, the best combination is at least {TARGET:g}x faster. Wall times "
              "include the set-up of each run (mesh, forms, first factorisation: about 2-3 s).", "",
              "| scene | thesis error | thesis wall s | fastest at or below that error | its error "
              "| its wall s | speed-up | target met |", "|---|---|---|---|---|---|---|---|",
              *summary, ""] + sections
    RESULTS.mkdir(parents=True, exist_ok=True)
    with open(RESULTS / "equal-error-speed.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in all_rows:
            w.writerow({**r, "wall_time_s": f"{r['wall_time_s']:.2f}", "error": f"{r['error']:.3e}",
                        "dt_or_tol": f"{r['dt_or_tol']:g}"})
        if partial:
            w.writerows(kept_rows)
    (RESULTS / "equal-error-speed.md").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
