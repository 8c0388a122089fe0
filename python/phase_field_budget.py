#!/usr/bin/python3
"""Where a cell's phase field sits: the area inside its zero level set and the part of
int (1 + phi)/2 that the bulk holds, from the last output time of a 2D run's fields.xdmf.

Usage: /usr/bin/python3 python/phase_field_budget.py RUN_DIR [RUN_DIR ...] [--bulk-level L]

The H^-1 flows keep int phi, and their bulk sits slightly above -1 (the diffuse
interface's Gibbs-Thomson shift): what the bulk holds, the cell's zero level set does not
enclose. On a cell's own mesh the bulk is the patch's, on the shared mesh the whole
domain's, so the two enclose different areas (demos/polar-gel-splay/README.md, "Where the
difference comes from"). The fields are read with python/cellphase_results.py and
integrated as piecewise linear on the output mesh (P2 fields are written on a refined P1 mesh): the area of
phi > 0 clipped exactly per triangle, the bulk being the triangles with phi < L at every
vertex (default L = -0.9, outside the band).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cellphase_results import read_fields  # noqa: E402


def last_fields(run_dir):
    """Points, triangles, phi and time of the last output of RUN_DIR (fields.xdmf, or the
    VTK index), read by the project's reader."""
    last = None
    for last in read_fields(run_dir, fields=["phi"]):
        pass  # keep only the last frame: a long run's frames need not fit in memory
    if last is None:
        sys.exit(f"phase_field_budget: {run_dir} has no output frames")
    time, points, cells, values = last
    if "phi" not in values:
        sys.exit(f"phase_field_budget: {run_dir} has no field phi at t = {time:g}")
    if cells.shape[1] != 3:
        sys.exit(f"phase_field_budget: {run_dir} is not a 2D triangle mesh")
    return points[:, :2], cells, np.asarray(values["phi"], dtype=float), float(time)


def triangle_areas(x, tri):
    a, b = x[tri[:, 1]] - x[tri[:, 0]], x[tri[:, 2]] - x[tri[:, 0]]
    return 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])


def area_above_zero(x, tri, f):
    """Area of {f > 0} for f linear on each triangle: all of it, none, or the corner
    triangle cut off by the zero line (its share is the product of the edge fractions)."""
    area = triangle_areas(x, tri)
    v = f[tri]
    positive = v > 0
    count = positive.sum(axis=1)
    total = area[count == 3].sum()
    for n_pos, lone_is_positive in ((1, True), (2, False)):
        rows = np.nonzero(count == n_pos)[0]
        if rows.size == 0:
            continue
        lone = np.argmax(positive[rows] == lone_is_positive, axis=1)
        others = [(lone + 1) % 3, (lone + 2) % 3]
        vl = v[rows, lone]
        share = np.ones(rows.size)
        for o in others:
            vo = v[rows, o]
            share *= vl / (vl - vo)  # fraction of the edge from the lone vertex to the zero
        corner = share * area[rows]
        total += corner.sum() if lone_is_positive else (area[rows] - corner).sum()
    return total


def budget(run_dir, bulk_level):
    x, tri, phi, time = last_fields(run_dir)
    area = triangle_areas(x, tri)
    content = ((1 + phi[tri]) / 2).mean(axis=1) * area  # exact for linear phi
    bulk = phi[tri].max(axis=1) < bulk_level
    return {"time": time, "volume": content.sum(), "inside": area_above_zero(x, tri, phi),
            "bulk": content[bulk].sum(), "bulk_area": area[bulk].sum()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="run directories (with fields.xdmf)")
    parser.add_argument("--bulk-level", type=float, default=-0.9,
                        help="the bulk: triangles with phi below this at every vertex")
    args = parser.parse_args()
    print("run | t | int (1 + phi)/2 | area inside phi > 0 | bulk holds | bulk area | mean 1 + phi in the bulk")
    for run in args.runs:
        b = budget(run, args.bulk_level)
        mean = 2 * b["bulk"] / b["bulk_area"] if b["bulk_area"] > 0 else float("nan")
        print(f"{run} | {b['time']:g} | {b['volume']:.4f} | {b['inside']:.4f} | {b['bulk']:.4f} | "
              f"{b['bulk_area']:.0f} | {mean:.2e}")


if __name__ == "__main__":
    main()
