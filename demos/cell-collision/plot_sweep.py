"""Fig. 7.6 from the interaction-strength sweep (interaction-sweep.yaml): the two cells at
the last output time of every member, strongest potential (smallest In) first, with the
zero level set (black) and the -0.8 level set (blue) of each cell's phase field, and the
largest overlap of the two cells over the run.

    /usr/bin/python3 demos/cell-collision/plot_sweep.py [SWEEP_DIR]
(default output/cell-collision/interaction-sweep; writes fig-7-6.png there)
"""
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
from cellphase_results import read_fields, read_observables  # noqa: E402


def main():
    sweep = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "output/cell-collision/interaction-sweep"
    members = sorted((d for d in sweep.glob("In=*") if d.is_dir()),
                     key=lambda d: float(d.name.split("=")[1]))
    if not members:
        raise SystemExit(f"{sweep}: no members In=...; run the study first (see README.md)")
    fig, axes = plt.subplots(len(members), 1, figsize=(6.5, 1.6 * len(members)),
                             constrained_layout=True, squeeze=False)
    for ax, member in zip(axes[:, 0], members):
        time, points, cells, values = list(read_fields(member))[-1]
        obs = read_observables(member)
        tri = mtri.Triangulation(points[:, 0], points[:, 1], cells)
        for name in ("phi_left", "phi_right"):
            ax.tricontour(tri, values[name], levels=[-0.8], colors="tab:blue", linewidths=0.8)
            ax.tricontour(tri, values[name], levels=[0.0], colors="k", linewidths=1.0)
        done = (member / "done").exists()
        ax.set_title(f"{member.name}: t = {time:.3g}{'' if done else ' (stopped: numerical failure)'}, "
                     f"largest overlap {max(obs['overlap_max']):.2f}", fontsize=8)
        ax.set(xlim=(1.0, 4.25), ylim=(0, 1.75), xticks=[], yticks=[])
        ax.set_aspect("equal")
    fig.suptitle("Interaction strength (thesis Fig. 7.6): smaller In, stronger repulsion", fontsize=9)
    out = sweep / "fig-7-6.png"
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
