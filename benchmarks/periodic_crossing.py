#!/usr/bin/python3
"""Translation invariance across a periodic face: the motile polar-gel cell crossing x = 160.

The splay scene (demos/polar-gel-splay, channel [0, 160] x [0, 40] periodic in x) at
eps = 0.42, dt = 0.14, base mesh 40 x 10, 1/Fa = 3 (fast, so that it crosses early), no
noise in P^0 (so that P^0 depends on y only) and the interior one level coarser, run to
t = 70 twice: the cell centred at x = 80, and at x = 152, shifted by 18 base cells (the same
base-mesh pattern under it). The shifted cell's front reaches the periodic face at t ~ 28 and
its back leaves it at t ~ 55. A translation-invariant discretisation gives both runs the same
v_cell up to the difference of their meshes, which is what the window before the crossing
(t < 20) shows.

Usage: /usr/bin/python3 benchmarks/periodic_crossing.py [--exe PATH] [--name NAME] [--report-only]
  --exe   the cellphase binary (default $CELLPHASE_EXE or build/cellphase)
  --name  a label for another build (e.g. --exe old/cellphase --name before-fix): its own
          report and plot beside the default ones.
  --report-only  the report and plot from the runs on disk.
Writes benchmarks/results/periodic-crossing[-NAME].md (its "## What it shows" section is
kept) and .png (v_cell of both runs and their difference against t). Members are kept in output/benchmarks/periodic-crossing[-NAME]/.
About 3 minutes on two cores (the two runs go side by side).
"""
import argparse
import csv
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "demos" / "polar-gel-splay" / "scene.yaml"
SETTINGS = ["numerics.epsilon=0.42", "numerics.dt=0.14", "domain.resolution=[40,10]",
            "polar_gel.activity=3", "polar_gel.initial.noise=0", "numerics.end_time=70",
            "numerics.mesh.inside_coarser_by=1", "output.every=0", "output.progress=false"]
CENTRES = (80, 152)
WINDOWS = ((0, 20), (20, 30), (30, 40), (40, 50), (50, 60), (60, 70.01))


def run_pair(exe, out):
    procs = []
    for cx in CENTRES:
        args = [str(exe), "run", str(SCENE)]
        for s in SETTINGS + [f"cells.0.center=[{cx},20]", f"output.directory={out / f'x{cx}'}"]:
            args += ["--set", s]
        procs.append(subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                      text=True, env={**os.environ, "OMP_NUM_THREADS": "1"}))
    for p in procs:
        log = p.communicate()[0]
        if p.returncode:
            sys.exit(f"periodic_crossing: a run failed:\n{log[-3000:]}")


def read(out, cx):
    with open(out / f"x{cx}" / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in ("time", "cell_velocity_x", "phi_min",
                                                       "center_x", "dofs")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", default=os.environ.get("CELLPHASE_EXE", ROOT / "build" / "cellphase"))
    ap.add_argument("--name", default="")
    ap.add_argument("--report-only", action="store_true",
                    help="only write the report and plot from the runs on disk")
    a = ap.parse_args()
    suffix = f"-{a.name}" if a.name else ""
    out = ROOT / "output" / "benchmarks" / f"periodic-crossing{suffix}"
    wall_file = out / "wall_s.txt"
    if not a.report_only:
        t0 = time.time()
        run_pair(a.exe, out)
        wall_file.write_text(f"{time.time() - t0:.1f}\n")
    wall = float(wall_file.read_text())
    here, shifted = read(out, CENTRES[0]), read(out, CENTRES[1])
    n = min(len(here["time"]), len(shifted["time"]))
    t = here["time"][:n]
    dv = [abs(x - y) for x, y in zip(here["cell_velocity_x"][:n], shifted["cell_velocity_x"][:n])]
    lines = [f"# Periodic crossing{': ' + a.name if a.name else ''}", "",
             f"Two runs side by side in {wall:.0f} s: the cell centred at "
             f"x = {CENTRES[0]} and at x = {CENTRES[1]} (crosses the periodic face x = 160); "
             "benchmarks/periodic_crossing.py says how.", "",
             "| t | shifted cell's front x_cm + 5 | max abs(dv_cell) | relative to v_cell | "
             "phi_min (x=80 / x=152) |", "|---|---|---|---|---|"]
    for lo, hi in WINDOWS:
        idx = [i for i in range(n) if lo <= t[i] < hi]
        if not idx:
            continue
        m = max(dv[i] for i in idx)
        mean_v = sum(abs(here["cell_velocity_x"][i]) for i in idx) / len(idx)
        front = sum(shifted["center_x"][i] for i in idx) / len(idx) + 5
        pa = min(here["phi_min"][i] for i in idx)
        pb = min(shifted["phi_min"][i] for i in idx)
        lines.append(f"| [{lo}, {hi:.0f}) | {front:.1f} | {m:.2e} | {m / mean_v:.2e} | "
                     f"{pa:.5f} / {pb:.5f} |")
    lines += ["", f"![v_cell of both runs and their difference](periodic-crossing{suffix}.png)"]
    text = "\n".join(lines) + "\n"
    results = ROOT / "benchmarks" / "results"
    report = results / f"periodic-crossing{suffix}.md"
    # A hand-written "## What it shows" section is kept.
    old = report.read_text() if report.exists() else ""
    keep = old[old.index("\n## What it shows"):] if "\n## What it shows" in old else ""
    report.write_text(text + keep)
    print(text)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    top.plot(t, here["cell_velocity_x"][:n], label=f"centred at x = {CENTRES[0]}")
    top.plot(t, shifted["cell_velocity_x"][:n], "--", label=f"centred at x = {CENTRES[1]}")
    # The start's swing (t < 2) is left out of the range.
    settled = [v for run in (here, shifted)
               for tt, v in zip(t, run["cell_velocity_x"][:n]) if tt >= 2]
    top.set_ylim(min(settled) - 0.02, max(settled) + 0.02)
    top.set_ylabel("v_cell")
    top.legend()
    bottom.semilogy(t, [max(d, 1e-16) for d in dv])
    bottom.set_ylabel("|difference of v_cell|")
    bottom.set_xlabel("t")
    for ax in (top, bottom):
        ax.axvspan(20, 55, color="0.9", zorder=0)  # the shifted cell's band on the face
    top.set_title("Cell crossing the periodic face x = 160 (shaded: its band on the face)"
                  + (f"\n{a.name}" if a.name else ""))
    fig.tight_layout()
    fig.savefig(results / f"periodic-crossing{suffix}.png", dpi=110)


if __name__ == "__main__":
    main()
