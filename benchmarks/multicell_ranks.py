"""Many cells on own meshes on 1 and 2 MPI ranks: what the second rank saves, by partition.

The scene of multicell_scaling.py (N circles in a Stokes flow, each on its own mesh) run
serially, then under `mpirun -n 2` with the meshes split by DOLFINx's graph partitioner and
in stripes (numerics.mesh.partition, the default with own meshes). The cells' phase fields
are solved one after the other, each on all ranks: a patch held mostly by one rank leaves
the other waiting, and stripes share every patch.

Writes benchmarks/results/multicell-ranks.{csv,md,png}:
n_cells,ranks,partition,dofs_total,wall_per_step_s,cells_part_s,flow_s,remesh_s,speedup,max_difference
(medians over the steps after the first; speedup = one rank's time per step / this one's;
max_difference: the largest difference of the observables from one rank's, relative to
max(1, |value|)).

    /usr/bin/python3 benchmarks/multicell_ranks.py [--cells 2 8 32] [--steps 6]
"""
import argparse
import csv
import time

from multicell_scaling import RESULTS, largest_difference, measure
from results_csv import hand_written_notes

VARIANTS = [(1, None), (2, "graph"), (2, "stripes")]


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cells", type=int, nargs="+", default=[2, 8, 32])
    p.add_argument("--steps", type=int, default=6)
    a = p.parse_args()
    rows = []
    for n in a.cells:
        serial = None
        for ranks, partition in VARIANTS:
            r = measure(n, a.steps, "own", ranks, partition)
            r.update(ranks=ranks, partition=partition or "-",
                     dofs_total=r["dofs_flow"] + r["dofs_cells_total"])
            serial = serial or r
            r["speedup"] = serial["wall_per_step_s"] / r["wall_per_step_s"]
            r["max_difference"] = largest_difference(serial["observables"], r["observables"])[0]
            rows.append(r)
            print(f"N = {n:3d}, {ranks} rank(s) {r['partition']:8s}: {r['wall_per_step_s']:.3f} s/step "
                  f"(cells {r['cells_part_s']:.3f}, flow {r['flow_s']:.3f}, remesh "
                  f"{r['remesh_s']:.3f}), speed-up {r['speedup']:.2f}, observables "
                  f"{r['max_difference']:.1e} from one rank", flush=True)
    keys = ["n_cells", "ranks", "partition", "dofs_total", "wall_per_step_s", "cells_part_s",
            "flow_s", "remesh_s", "speedup", "max_difference"]
    with open(RESULTS / "multicell-ranks.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.6))
    for partition, style in [("graph", "s--"), ("stripes", "o-")]:
        sel = [r for r in rows if r["partition"] == partition]
        ax.semilogx([r["n_cells"] for r in sel], [r["speedup"] for r in sel], style,
                    label=f"2 ranks, {partition}")
    ax.axhline(1, color="k", lw=0.8, ls=":")
    ax.axhline(2, color="k", lw=0.8, ls=":")
    ax.set_xticks(a.cells)
    ax.set_xticklabels([str(n) for n in a.cells])
    ax.minorticks_off()
    ax.set_xlabel("cells N")
    ax.set_ylabel("speed-up over one rank (time per step)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(RESULTS / "multicell-ranks.png", dpi=120)

    lines = ["# Many cells on own meshes: one rank against two", "",
             f"{time.strftime('%Y-%m-%d')}, this machine (2 cores), one BLAS thread per rank, "
             f"`benchmarks/multicell_ranks.py --cells {' '.join(map(str, a.cells))} --steps {a.steps}`.",
             "The scene of multicell-scaling.md; medians over the steps after the first.", "",
             "| N | ranks | partition | dofs | s/step | cells' part s | flow s | remesh s | "
             "speed-up | observables from 1 rank |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['n_cells']} | {r['ranks']} | {r['partition']} | {r['dofs_total']} | "
                     f"{r['wall_per_step_s']:.3f} | {r['cells_part_s']:.3f} | {r['flow_s']:.3f} | "
                     f"{r['remesh_s']:.3f} | {r['speedup']:.2f} | {r['max_difference']:.1e} |")
    lines += ["", "![speed-up against N](multicell-ranks.png)", ""]
    report = RESULTS / "multicell-ranks.md"
    notes = hand_written_notes(report)
    report.write_text("\n".join(lines) + ("\n" + notes if notes else ""))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
