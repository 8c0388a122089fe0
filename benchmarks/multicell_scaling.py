"""Time per step against the number of cells (issue: many cells on a modular core).

N = 1, 2, 4, ... circles of radius 0.25 on a square lattice of spacing 0.8 (a fixed area
fraction: the domain grows with N), each its own phase field (helfrich_hm1 with the
repulsive interaction), in a Stokes flow with no-slip walls, serial. Each cell is solved on
its own mesh (numerics.mesh.cell_meshes: own), and up to --shared-up-to cells also on the
one mesh refined around all cells (cell_meshes: shared), side by side in the same run, with
the largest difference of the observables between the two at the largest such N.

Writes benchmarks/results/multicell-scaling.{csv,md,png}:
n_cells,dofs_flow,dofs_cells_total,wall_per_step_s,cells_part_s,flow_s,remesh_s,cell_meshes
(medians over the steps after the first), and the fitted exponents.

    /usr/bin/python3 benchmarks/multicell_scaling.py [--cells 1 2 4 8] [--steps 6]
                                                     [--shared-up-to 8]
"""
import argparse
import csv
import math
import os
import pathlib
import statistics
import subprocess
import time

import yaml

from results_csv import hand_written_notes

ROOT = pathlib.Path(__file__).resolve().parents[1]
# $CELLPHASE_EXE runs a copy, so that a rebuild cannot replace the binary under a running study
EXE = pathlib.Path(os.environ.get("CELLPHASE_EXE", ROOT / "build" / "cellphase"))
RESULTS = ROOT / "benchmarks" / "results"
OUT = ROOT / "output" / "benchmarks" / "multicell"


def run_name(n, meshes, ranks=1, partition=None):
    return f"{meshes}-n{n}" + (f"-{ranks}ranks-{partition}" if ranks > 1 else "")


def scene(n, steps, meshes, ranks=1, partition=None):
    side = math.ceil(math.sqrt(n))
    rows = math.ceil(n / side)
    spacing = 0.8
    cells = [{"name": f"c{i}", "shape": "circle", "radius": 0.25,
              "center": [spacing * (i % side + 0.5), spacing * (i // side + 0.5)]}
             for i in range(n)]
    s = {
        "domain": {"lower": [0, 0], "upper": [spacing * side, spacing * rows],
                   "resolution": [6 * side, 6 * rows]},
        "cells": cells,
        "phase_field": {"model": "helfrich_hm1", "mobility": 1e-3, "penalty_area": 100},
        "numbers": {"Be": 10.0},
        "interaction": {"In": 0.1},
        "flow": {"equations": "stokes", "force": [1.0, 0.0]},
        "numerics": {"epsilon": 0.04, "dt": 5e-3, "end_time": steps * 5e-3,
                     "mesh": {"remesh_every": 3, "points_across_interface": 4,
                              "cell_meshes": meshes}},
        "output": {"directory": str(OUT / run_name(n, meshes, ranks, partition)), "every": 0,
                   "progress": False},
    }
    if partition:
        s["numerics"]["mesh"]["partition"] = partition
    if n == 1:
        del s["interaction"]  # nothing to interact with
    return s


def measure(n, steps, meshes, ranks=1, partition=None):
    """Run the N-cell scene (on `ranks` MPI ranks, the meshes split by `partition` or the
    default) and return its sizes and median timings per step."""
    OUT.mkdir(parents=True, exist_ok=True)
    name = run_name(n, meshes, ranks, partition)
    path = OUT / f"{name}.yaml"
    path.write_text(yaml.safe_dump(scene(n, steps, meshes, ranks, partition)))
    args = [str(EXE), "run", str(path)]
    if ranks > 1:
        root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
        args = ["mpirun", *root, "-x", "OMP_NUM_THREADS", "-n", str(ranks)] + args
    t0 = time.time()
    # One BLAS thread: more spin in sched_yield on a 2-core machine (40 % of the samples).
    proc = subprocess.run(args, capture_output=True, text=True,
                          env={**os.environ, "OMP_NUM_THREADS": "1"})
    if proc.returncode != 0:
        raise SystemExit(f"cellphase failed on {path}:\n{proc.stdout}{proc.stderr}")
    wall = time.time() - t0
    with open(OUT / name / "observables.csv") as f:
        every_row = list(csv.DictReader(f))
    rows = every_row[2:]  # steps 2.. (step 1 builds the solvers)
    col = lambda k: [float(r[k]) for r in rows]  # noqa: E731
    total = [a + f + s + m for a, f, s, m in zip(col("wall_assembly"), col("wall_factorise"),
                                                 col("wall_solve"), col("wall_remesh"))]
    flow = col("wall_flow")
    cells = [a + f + s - w for a, f, s, w in zip(col("wall_assembly"), col("wall_factorise"),
                                                 col("wall_solve"), flow)]
    dofs, flow_dofs = int(float(rows[-1]["dofs"])), int(float(rows[-1]["flow_dofs"]))
    return {"n_cells": n, "dofs_flow": flow_dofs, "dofs_cells_total": dofs - flow_dofs,
            "wall_per_step_s": statistics.median(total), "cells_part_s": statistics.median(cells),
            "flow_s": statistics.median(flow),
            "remesh_s": statistics.mean(col("wall_remesh")), "run_s": wall,
            "cell_meshes": meshes, "observables": every_row}


def largest_difference(a, b, keep=lambda k: True):
    """Largest difference of the observables (not timings, not dofs) of two runs, relative
    to max(1, |value|), and its column; `keep` selects the columns."""
    worst, where = 0.0, ""
    for k in a[0]:
        if k.startswith("wall_") or k in ("dofs", "flow_dofs", "remesh_volume_change",
                                          "inclination_deg") or not keep(k) or k not in b[0]:
            continue
        for ra, rb in zip(a, b):
            x, y = float(ra[k]), float(rb[k])
            d = abs(x - y) / max(1.0, abs(x))
            if d > worst:
                worst, where = d, k
    return worst, where


def exponent(rows, key, lo, hi=math.inf):
    pts = [(math.log(r["n_cells"]), math.log(r[key])) for r in rows if lo <= r["n_cells"] <= hi]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cells", type=int, nargs="+", default=[1, 2, 4, 8])
    p.add_argument("--steps", type=int, default=6)
    p.add_argument("--shared-up-to", type=int, default=8,
                   help="also run cell_meshes: shared up to this N (its cost grows as N^2)")
    a = p.parse_args()
    all_rows = []
    for n in a.cells:
        for meshes in ["own"] + (["shared"] if n <= a.shared_up_to else []):
            r = measure(n, a.steps, meshes)
            all_rows.append(r)
            print(f"N = {n:3d} {meshes:6s}: {r['dofs_cells_total']:8d} cell dofs, "
                  f"{r['dofs_flow']:7d} flow dofs, {r['wall_per_step_s']:.3f} s/step (cells "
                  f"{r['cells_part_s']:.3f}, flow {r['flow_s']:.3f}, remesh {r['remesh_s']:.3f}), "
                  f"run {r['run_s']:.0f} s", flush=True)
    rows = [r for r in all_rows if r["cell_meshes"] == "own"]
    shared = [r for r in all_rows if r["cell_meshes"] == "shared"]
    RESULTS.mkdir(parents=True, exist_ok=True)
    keys = ["n_cells", "dofs_flow", "dofs_cells_total", "wall_per_step_s", "cells_part_s",
            "flow_s", "remesh_s", "cell_meshes"]
    with open(RESULTS / "multicell-scaling.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(all_rows)
    # The targets are stated from 4 to 32 cells; beyond, the fit from 16 shows whether the
    # cost per cell still grows once most cells are inside the lattice.
    lo, hi = (4 if max(a.cells) > 4 else 1), 32
    e_step, e_cells = exponent(rows, "wall_per_step_s", lo, hi), exponent(rows, "cells_part_s", lo, hi)
    e_dofs = exponent(rows, "dofs_cells_total", lo, hi)
    big = [r for r in rows if r["n_cells"] >= 16]
    e_cells_big = exponent(rows, "cells_part_s", 16) if len(big) >= 2 else None
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = [r["n_cells"] for r in rows]
    fig, ax = plt.subplots(figsize=(5, 4))
    for key, label in [("wall_per_step_s", f"whole step, own meshes (exponent {e_step:.2f}, N = {lo}-{hi})"),
                       ("cells_part_s", f"cells' part, own meshes (exponent {e_cells:.2f}, N = {lo}-{hi})"),
                       ("flow_s", "flow")]:
        ax.loglog(n, [r[key] for r in rows], "o-", label=label)
    if shared:
        ax.loglog([r["n_cells"] for r in shared], [r["wall_per_step_s"] for r in shared], "s--",
                  label="whole step, shared mesh")
    ax.loglog(n, [rows[0]["cells_part_s"] * x for x in n], "k:", label="linear in N")
    ax.set_xlabel("cells N")
    ax.set_ylabel("wall time per step [s]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(RESULTS / "multicell-scaling.png", dpi=120)
    lines = ["# Time per step against the number of cells", "",
             f"{time.strftime('%Y-%m-%d')}, this machine (2 cores, shared), serial (one BLAS thread), "
             f"`benchmarks/multicell_scaling.py --cells {' '.join(map(str, a.cells))} --steps {a.steps} "
             f"--shared-up-to {a.shared_up_to}`.",
             "own: each cell's phase field on its own mesh (patch of the base mesh refined around "
             "that cell); shared: on the one mesh refined around all cells.", "",
             "| N | cell meshes | flow dofs | cell dofs (all) | s/step | cells' part s | flow s | remesh s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in all_rows:
        lines.append(f"| {r['n_cells']} | {r['cell_meshes']} | {r['dofs_flow']} | "
                     f"{r['dofs_cells_total']} | {r['wall_per_step_s']:.3f} | "
                     f"{r['cells_part_s']:.3f} | {r['flow_s']:.3f} | {r['remesh_s']:.3f} |")
    if shared:
        m = max(r["n_cells"] for r in shared)
        own_m = next(r for r in rows if r["n_cells"] == m)
        sh_m = next(r for r in shared if r["n_cells"] == m)
        diff, col = largest_difference(own_m["observables"], sh_m["observables"])
        lines += ["", f"Side by side at N = {m}: own meshes {own_m['dofs_cells_total']} cell dofs, "
                  f"{own_m['wall_per_step_s']:.3f} s/step; shared mesh {sh_m['dofs_cells_total']} "
                  f"cell dofs, {sh_m['wall_per_step_s']:.3f} s/step (ratio "
                  f"{sh_m['wall_per_step_s'] / own_m['wall_per_step_s']:.1f}); largest difference "
                  f"of the observables {diff:.1e} ({col}, relative to max(1, |value|))."]
        kinds = [("total energy", lambda k: k == "total_energy"),
                 ("centres", lambda k: ".center_" in k), ("volumes", lambda k: k.endswith(".volume")),
                 ("Helfrich energies", lambda k: k.endswith(".helfrich_energy")),
                 ("overlap", lambda k: k == "overlap_max"),
                 ("area multipliers", lambda k: k.endswith(".lambda_area"))]
        lines += ["By quantity: " + ", ".join(
            f"{name} {largest_difference(own_m['observables'], sh_m['observables'], keep)[0]:.1e}"
            for name, keep in kinds) + "."]
    lines += ["", "Per cell: " + ", ".join(
        f"N = {r['n_cells']}: {r['cells_part_s'] / r['n_cells'] * 1e3:.1f} ms, "
        f"{r['dofs_cells_total'] // r['n_cells']} dofs" for r in rows) + "."]
    lines += ["", f"Fitted exponents (own meshes) from N = {lo} to {min(hi, max(a.cells))}: whole "
              f"step {e_step:.2f}, cells' part {e_cells:.2f}, cell dofs {e_dofs:.2f} (targets: "
              f"cells' part <= 1.1, step <= 1.3)."
              + (f" From N = 16 to {max(a.cells)}: cells' part {e_cells_big:.2f}."
                 if e_cells_big is not None else ""),
              f"Flow share of the step at the largest N: "
              f"{rows[-1]['flow_s'] / rows[-1]['wall_per_step_s']:.0%}.", "",
              "![time per step](multicell-scaling.png)", ""]
    report = RESULTS / "multicell-scaling.md"
    notes = hand_written_notes(report)
    notes = "\n" + notes if notes else ""
    report.write_text("\n".join(lines) + notes)
    print("\n".join(lines[-6:]))


if __name__ == "__main__":
    main()
