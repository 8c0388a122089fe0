"""Eight red blood cells in the bifurcated vessel with the two interaction potentials of
Fig. 7.7b (thesis section 7.3.2): the repulsive Gaussian w_j (7.2) (r1 = 1, r2 = 4, a1 = 0)
and the Lennard-Jones-like w-bar_j (r1 = 2, r2 = 1, a1 = 1, a2 = 0, a3 = 20), eps = 0.04.

Runs them from demos/rbc-bifurcation/scene.yaml (one per core), then draws
output/rbc-bifurcation/fig-7-7b.png: one row per potential, one column per time, the zero
level sets of the cells on the flow speed |v|, and prints the overlap and the cells' mean
velocity at those times.

    /usr/bin/python3 demos/rbc-bifurcation/run_potentials.py [--plot-only]
                  [--potentials repulsive lennard_jones] [--times T ...] [--set KEY=VALUE ...]
"""
import argparse
import pathlib
import sys

import numpy as np
import yaml

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "python"))
from cellphase_results import read_observables  # noqa: E402
from demo_variants import frames_at, run_all, run_variant  # noqa: E402

OUT = ROOT / "output" / "rbc-bifurcation"
POTENTIALS = {
    "repulsive": {"potential": "repulsive", "r1": 1, "r2": 4},
    # with the scene's derivative_reach 3 and flow_force false (docs/scenes.md, interaction)
    "lennard_jones": {"potential": "lennard_jones", "r1": 2, "r2": 1, "a1": 1, "a2": 0, "a3": 20},
}


def run(name, overrides):
    scene = yaml.safe_load((HERE / "scene.yaml").read_text())
    scene["interaction"].update(POTENTIALS[name])  # meshes/NAME.xdmf is found from anywhere
    scene["output"]["directory"] = str(OUT / name)
    return run_variant(scene, OUT, name, overrides)


def draw(names, times):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    fig, axes = plt.subplots(len(names), len(times), figsize=(3.3 * len(times), 2.9 * len(names)),
                             squeeze=False, constrained_layout=True)
    for row, name in enumerate(names):
        for col, (t, points, cells, values) in enumerate(frames_at(OUT / name, times, ["phi_cells", "v"])):
            ax = axes[row][col]
            tri = mtri.Triangulation(points[:, 0], points[:, 1], cells[:, :3])
            speed = np.linalg.norm(values["v"][:, :2], axis=1)
            pc = ax.tripcolor(tri, speed, shading="gouraud", cmap="Blues", vmin=0, vmax=6)
            ax.tricontour(tri, values["phi_cells"], levels=[0.0], colors="k", linewidths=0.8)
            ax.set(xlim=(0, 5.5), ylim=(-1.6, 1.6), xticks=[], yticks=[])  # the cells' reach by t = 0.6
            ax.set_aspect("equal")
            if row == 0:
                ax.set_title(f"t = {t:.2f}", fontsize=9)
            if col == 0:
                ax.set_ylabel(name.replace("_", "-"), fontsize=9)
    fig.colorbar(pc, ax=axes, shrink=0.6, label="|v|")
    fig.suptitle("Eight RBCs in a bifurcated vessel (thesis Figs. 7.5 and 7.7b), from the top: "
                 + ", ".join(n.replace("_", "-") for n in names) + " interaction", fontsize=9)
    path = OUT / "fig-7-7b.png"
    fig.savefig(path, dpi=90)
    print(f"wrote {path}")


def summary(names, times):
    for name in names:
        obs = read_observables(OUT / name)
        t = obs["time"]
        for want in times:
            k = int(np.argmin(np.abs(t - want)))
            print(f"{name:14s} t = {t[k]:.3f}: overlap_max {obs['overlap_max'][k]:.3f}, "
                  f"cells' mean x-velocity {obs['cell_velocity_x'][k]:.3f}, "
                  f"interaction energy {obs['interaction_energy'][k]:.1f}")
        v = obs["volume"]
        print(f"{name:14s} volume kept to {np.max(np.abs(v / v[0] - 1)):.1e} up to t = {t[-1]:.3f}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--plot-only", action="store_true", help="draw the figure from earlier runs")
    p.add_argument("--potentials", nargs="+", default=list(POTENTIALS), choices=list(POTENTIALS))
    p.add_argument("--times", type=float, nargs="+", default=[0.0, 0.2, 0.4, 0.6])
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override for both runs (as cellphase run --set)")
    a = p.parse_args()
    names = a.potentials
    if not a.plot_only:
        runs = {n: (lambda n=n: run(n, a.set)) for n in names}
        for name, rc in run_all(runs):
            print(f"{name}: " + ("done" if rc == 0 else f"stopped (exit {rc}), see {OUT / (name + '.log')}"))
    draw(names, a.times)
    summary(names, a.times)


if __name__ == "__main__":
    main()
