#!/usr/bin/python3
"""The critical activity against the viscosities inside and outside the cell (thesis Fig.
6.12, section 6.4.4), gathered from the bisections of benchmarks/polar_critical.py.

Each viscosity setting is one bisection run with --set "flow.viscosity={...}" and a --name of
its own (SETTINGS below lists them with the commands); this script reads their result tables
and writes benchmarks/results/polar-viscosity-ratios.csv
(eta_outside,eta_inside,epsilon,inv_fa_crit,bracket_lo,bracket_hi), .md and .png (1/Fa_crit
for each setting). A setting whose table is missing is listed as not run.

Usage: /usr/bin/python3 benchmarks/polar_viscosity_ratios.py
"""
import csv
import sys
from pathlib import Path

from results_csv import write_csv

RESULTS = Path(__file__).resolve().parent / "results"
EPSILON = 0.42
# (eta_outside, eta_inside, result name of polar_critical.py)
SETTINGS = [(1.0, 1.0, "polar-critical"),
            (0.5, 0.5, "polar-critical-viscosity"),
            (1.0, 2.0, "polar-critical-viscosity-inside2"),
            (1.0, 0.5, "polar-critical-viscosity-inside05")]
COLUMNS = ["eta_outside", "eta_inside", "epsilon", "inv_fa_crit", "bracket_lo", "bracket_hi"]


def command(eta_out, eta_in, name):
    return (f"/usr/bin/python3 benchmarks/polar_critical.py --epsilons {EPSILON} --set "
            f"\"flow.viscosity={{inside: {eta_in:g}, outside: {eta_out:g}}}\" --name {name}")


def gather():
    rows, missing = [], []
    for eta_out, eta_in, name in SETTINGS:
        path = RESULTS / f"{name}.csv"
        found = []
        if path.exists():
            with open(path) as f:
                found = [r for r in csv.DictReader(f) if float(r["epsilon"]) == EPSILON]
        if not found:
            missing.append((eta_out, eta_in, name))
            continue
        r = found[0]
        rows.append({"eta_outside": eta_out, "eta_inside": eta_in, "epsilon": EPSILON, "name": name,
                     **{k: float(r[k]) for k in ("inv_fa_crit", "bracket_lo", "bracket_hi")}})
    return rows, missing


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 3.4), constrained_layout=True)
    labels = [f"eta_0 = {r['eta_outside']:g}\neta_1 = {r['eta_inside']:g}" for r in rows]
    mid = [r["inv_fa_crit"] for r in rows]
    half = [(r["bracket_hi"] - r["bracket_lo"]) / 2 for r in rows]
    ax.errorbar(range(len(rows)), mid, yerr=half, fmt="o", capsize=4)
    ax.set_xticks(range(len(rows)), labels)
    ax.set_xlim(-0.5, len(rows) - 0.5)
    ax.set_ylabel("1/Fa_crit")
    ax.set_title(f"Critical activity against the viscosities (Fig. 6.12), eps = {EPSILON}",
                 fontsize=9)
    fig.savefig(path, dpi=100)


def main():
    rows, missing = gather()
    if not rows:
        sys.exit("no bisection results found; run:\n" + "\n".join(command(*s) for s in SETTINGS))
    write_csv(RESULTS / "polar-viscosity-ratios.csv", COLUMNS, rows)
    plot(rows, RESULTS / "polar-viscosity-ratios.png")
    lines = ["# Critical activity against the viscosities (thesis Fig. 6.12)", "",
             "Written by `benchmarks/polar_viscosity_ratios.py` from the bisections of "
             "`benchmarks/polar_critical.py` (beta = 0, the 30 x 20 cell of the bifurcation "
             f"diagram, eps = {EPSILON}, each to +-0.016). eta_0 is the viscosity outside the "
             "cell, eta_1 inside, both relative to the reference viscosity of the flow's Re.", "",
             "| eta_0 (outside) | eta_1 (inside) | 1/Fa_crit | bracket | run with |",
             "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['eta_outside']:g} | {r['eta_inside']:g} | {r['inv_fa_crit']:.3f} | "
                     f"({r['bracket_lo']:.4g}, {r['bracket_hi']:.4g}) | `{r['name']}.md` |")
    for s in missing:
        lines.append(f"| {s[0]:g} | {s[1]:g} | not run | | `{command(*s)}` |")
    lines += ["", "The thesis (section 6.4.4): equal viscosities lowered together lower the "
              "critical activity; a more viscous cytoplasm with the outside fluid unchanged "
              "raises it.", "", "![1/Fa_crit against the viscosities](polar-viscosity-ratios.png)"]
    (RESULTS / "polar-viscosity-ratios.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
