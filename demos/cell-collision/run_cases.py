"""The six cases of Fig. 7.3 (thesis section 7.3.1) from demos/cell-collision/scene.yaml:

  (a) one phase field for both cells          (b) the same with inextensibility
  (c) two phase fields                        (d) the same with inextensibility
  (e) two phase fields and the potential      (f) the same with inextensibility

Runs them (two at a time), then draws output/cell-collision/fig-7-3.png: one row per case,
one column per time (0.2, 0.4, 0.6 and the end), with the streamlines of v, the zero level
set of the cells' phase field (black) and its -0.8 level set (blue), as in Fig. 7.3.

    /usr/bin/python3 demos/cell-collision/run_cases.py [--cases a b c d e f] [--plot-only]
                                                       [--set KEY=VALUE ...]
"""
import argparse
import copy
import pathlib
import sys

import numpy as np
import yaml

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "python"))
from demo_variants import frames_at, run_all, run_variant  # noqa: E402

OUT = ROOT / "output" / "cell-collision"
CASES = {
    "a": "one phase field",
    "b": "one phase field, inextensible",
    "c": "two phase fields",
    "d": "two phase fields, inextensible",
    "e": "two phase fields, interaction (In = 0.01)",
    "f": "two phase fields, interaction, inextensible",
}
TIMES = [0.2, 0.4, 0.6, None]  # None: the end of the run


def case_scene(base, case):
    s = copy.deepcopy(base)
    if case in "ab":
        for c in s["cells"]:
            c["group"] = "cells"  # both shapes in one phase field, case (a) of Fig. 7.3
    if case in "abcd":
        s.pop("interaction", None)
    if case in "bdf":
        s["flow"]["inextensibility"] = {"xi": 1}  # local inextensibility (7.14)-(7.16)
    if case == "a":  # one phase field and no constraint: no union phi_cells, phi is it
        s["output"]["fields"] = [f for f in s["output"]["fields"] if f != "phi_cells"]
    s["output"]["directory"] = str(OUT / case)
    return s


def run(case, overrides):
    scene = case_scene(yaml.safe_load((HERE / "scene.yaml").read_text()), case)
    return run_variant(scene, OUT, f"case-{case}", overrides)


def snapshot(run_dir, wanted):
    """The output frames nearest to the wanted times (None: the last one), and the name
    of the cells' phase field in them."""
    frames = frames_at(run_dir, wanted)
    phase = "phi_cells" if "phi_cells" in frames[0][3] else "phi"
    return [(frame, phase) for frame in frames]


def draw(cases):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    fig, axes = plt.subplots(len(cases), len(TIMES), figsize=(3.2 * len(TIMES), 1.25 * len(cases) + 0.4),
                             squeeze=False, constrained_layout=True)
    for row, case in enumerate(cases):
        for col, ((time, points, cells, values), phase) in enumerate(snapshot(OUT / case, TIMES)):
            ax = axes[row][col]
            tri = mtri.Triangulation(points[:, 0], points[:, 1], cells[:, :3])
            if "v" in values:
                # Streamlines on a regular grid (linear interpolation of the P2 nodes' values).
                gx, gy = np.meshgrid(np.linspace(0, 5.25, 106), np.linspace(0, 1.75, 36))
                v = values["v"]
                u = mtri.LinearTriInterpolator(tri, v[:, 0])(gx, gy)
                w = mtri.LinearTriInterpolator(tri, v[:, 1])(gx, gy)
                ax.streamplot(gx, gy, u.filled(0), w.filled(0), density=0.7, color="0.6",
                              linewidth=0.5, arrowsize=0.5)
            ax.tricontour(tri, values[phase], levels=[-0.8], colors="tab:blue", linewidths=0.8,
                          linestyles="solid")
            ax.tricontour(tri, values[phase], levels=[0.0], colors="k", linewidths=1.0)
            ax.set(xlim=(0, 5.25), ylim=(0, 1.75), xticks=[], yticks=[])
            ax.set_aspect("equal")
            if row == 0:
                ax.set_title(f"t = {time:g}", fontsize=9)
            if col == 0:
                ax.set_ylabel(f"({case})", rotation=0, labelpad=12, fontsize=9)
    fig.suptitle("Two cells pushed together (thesis Fig. 7.3): " + "; ".join(
        f"({c}) {CASES[c]}" for c in cases), fontsize=7)
    path = OUT / "fig-7-3.png"
    fig.savefig(path, dpi=90)
    print(f"wrote {path}")


def summary(cases):
    """output/cell-collision/summary.md: per case the largest overlap of the two phase
    fields (none with one), at t = 0.6 and over the run, and the volume kept."""
    from cellphase_results import read_observables
    lines = ["| case | overlap_max at t = 0.6 | largest overlap_max | volume change |",
             "|---|---|---|---|"]
    for case in cases:
        obs = read_observables(OUT / case)
        t = obs["time"]
        k = min(range(len(t)), key=lambda i: abs(t[i] - 0.6))
        v = obs["volume"]
        if "overlap_max" in obs:
            at, top = f"{obs['overlap_max'][k]:.3f}", f"{max(obs['overlap_max']):.3f}"
        else:
            at = top = "- (one phase field)"
        lines.append(f"| ({case}) {CASES[case]} | {at} | {top} | {abs(v[-1] / v[0] - 1):.1e} |")
    (OUT / "summary.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    p.add_argument("--plot-only", action="store_true", help="draw the figure from earlier runs")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override for every case (as cellphase run --set)")
    p.add_argument("--parallel", type=int, default=2, help="cases run at the same time")
    a = p.parse_args()
    done = a.cases
    if not a.plot_only:
        done = []
        runs = {c: (lambda c=c: run(c, a.set)) for c in a.cases}
        for case, rc in run_all(runs, a.parallel):
            print(f"case ({case}) {CASES[case]}: "
                  + ("done" if rc == 0 else f"failed (exit {rc}), see {OUT / f'case-{case}.log'}"),
                  flush=True)
            if rc == 0:
                done.append(case)
    if not done:
        raise SystemExit("no case finished: nothing to draw")
    draw(done)
    summary(done)


if __name__ == "__main__":
    main()
