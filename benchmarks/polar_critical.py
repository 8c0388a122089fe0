#!/usr/bin/python3
"""Critical activity of the active polar gel cell by bisection (thesis Fig. 6.10, section 6.4.2).

For beta = 0 the onset of motility is a pitchfork: below 1/Fa_crit a perturbed cell comes to
rest, above it the splay mode grows. Each bisection member runs the cell of
benchmarks/studies/polar-bifurcation.yaml (30 x 20 channel, splay seed 0.1) to t = 50 and fits
ln |v_cell| linearly over t in [20, 50]: after the start-up transient (t < 20) and before the
saturation of a growing mode, the slope is the growth rate of the splay mode. A positive rate
classes the member as moving, a negative one as at rest, so a member needs 50 time units
instead of the up to 150 a member of the diagram needs to settle near the onset. The bracket
is halved (with --jobs N split into N + 1 parts) until it is at most 2 x TOL wide; its
midpoint is 1/Fa_crit +- TOL. The zero of the growth rate interpolated linearly between the
last bracket's ends is reported beside it.

The time step follows the mesh (thesis section 6.4.3: the same relation between mesh size and
time step for every eps): dt = 0.1 eps / 0.42.

Usage: /usr/bin/python3 benchmarks/polar_critical.py [--epsilons 0.42 0.3] [--bracket LO HI]
                                                     [--tolerance 0.02] [--jobs N]
                                                     [--set KEY=VALUE ...]
                                                     [--name NAME] [--report-only]

Epsilons run one after the other; --jobs 2 runs two members of one eps side by side (the
bracket's ends, then two points a round that leave a third of the bracket), or start one
process per eps and write the joint tables afterwards with --report-only --epsilons 0.42 0.3
(it reuses the members). The committed rows of the epsilons not run are kept in the tables.
--set changes the scene of every member (e.g. --set "flow.viscosity={inside: 2, outside: 1}"
for the viscosity study of Fig. 6.12); such members get their own directories, and --name
gives the results their own file names.

Writes benchmarks/results/polar-critical.csv (beta,epsilon,inv_fa_crit,bracket_lo,bracket_hi,
inv_fa_zero_rate,members,wall_time_s), polar-critical-members.csv (every member's growth
rate), polar-critical.md (its hand-written "## What it shows" section kept) and
polar-critical.png (growth rate against 1/Fa per eps, and 1/Fa_crit against eps). Members
are kept in output/benchmarks/polar-critical/ and reused.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from results_csv import write_csv, write_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# $CELLPHASE_EXE runs a copy, so that a rebuild cannot replace the binary under a running study
EXE = Path(os.environ.get("CELLPHASE_EXE", ROOT / "build" / "cellphase"))
SCENE = ROOT / "demos" / "polar-gel-splay" / "scene.yaml"
WORK = ROOT / "output" / "benchmarks" / "polar-critical"
RESULTS = ROOT / "benchmarks" / "results"
WINDOW = (20.0, 50.0)  # fit window of ln |v_cell|: after the transient, before saturation
BETA = 0  # the sharp onset exists for beta = 0 only (Fig. 6.8)
# the cell of the bifurcation diagram (benchmarks/studies/polar-bifurcation.yaml)
SETTINGS = {"domain.upper": "[30,20]", "domain.resolution": "[10,7]",
            "cells.0.center": "[15,10]", "polar_gel.initial.splay": 0.1,
            "polar_gel.beta": BETA, "numerics.end_time": WINDOW[1], "output.every": 0,
            "output.progress": "false", "output.checkpoints.every": 0}
MEMBER_COLUMNS = ["beta", "epsilon", "inv_fa", "growth_rate", "dt", "dofs", "wall_time_s"]
COLUMNS = ["beta", "epsilon", "inv_fa_crit", "bracket_lo", "bracket_hi", "inv_fa_zero_rate",
           "members", "wall_time_s"]


def time_step(eps):
    return 0.1 * eps / 0.42


def growth_rate(times, speeds):
    """Least-squares slope of ln |v_cell| against t over WINDOW."""
    pts = [(t, math.log(abs(v))) for t, v in zip(times, speeds)
           if WINDOW[0] - 1e-9 <= t <= WINDOW[1] + 1e-9 and v != 0]
    if len(pts) < 3:
        raise RuntimeError(f"fewer than 3 nonzero rows of cell_velocity_x in t = {WINDOW}")
    mt = sum(t for t, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return (sum((t - mt) * (y - my) for t, y in pts)
            / sum((t - mt) ** 2 for t, _ in pts))


def member_tag(extra):
    """The part of a member's directory name that the --set settings make."""
    tag = "".join(f"_{k}={v}" for k, v in extra.items())
    return "".join(c if c.isalnum() or c in "._=-" else "" for c in tag)


def read_member(done):
    with open(done) as f:
        row = next(csv.DictReader(f))
    return {k: float(v) for k, v in row.items()}


def member(eps, inv_fa, extra):
    """Run (or reuse) one member (extra: settings of --set); its row of the members' table."""
    out = WORK / f"eps={eps:g}_beta={BETA:g}_activity={inv_fa:.6g}{member_tag(extra)}"
    done = out / "member.csv"
    if done.exists():
        return read_member(done)
    out.mkdir(parents=True, exist_ok=True)
    settings = {**SETTINGS, "numerics.epsilon": eps, "numerics.dt": f"{time_step(eps):.10g}",
                "polar_gel.activity": f"{inv_fa:.10g}", **extra, "output.directory": out}
    args = [str(EXE), "run", str(SCENE)]
    for key, value in settings.items():
        args += ["--set", f"{key}={value}"]
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True,
                          env={**os.environ, "OMP_NUM_THREADS": "1",
                               "OPENBLAS_NUM_THREADS": "1"})
    wall = time.perf_counter() - t0
    (out / "stdout.txt").write_text(proc.stdout)
    (out / "stderr.txt").write_text(proc.stderr)
    if proc.returncode != 0:
        sys.exit(f"member eps {eps:g}, 1/Fa {inv_fa:g} failed (exit {proc.returncode}); see "
                 f"{out}/stderr.txt:\n{proc.stderr[-2000:]}")
    with open(out / "observables.csv") as f:
        rows = list(csv.DictReader(f))
    times = [float(r["time"]) for r in rows]
    speeds = [float(r["cell_velocity_x"]) for r in rows]
    dofs = int(float(rows[-1].get("dofs", 0) or 0))
    row = {"beta": BETA, "epsilon": eps, "inv_fa": inv_fa,
           "growth_rate": growth_rate(times, speeds), "dt": time_step(eps), "dofs": dofs,
           "wall_time_s": wall}
    with open(done, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=MEMBER_COLUMNS)
        writer.writeheader()
        writer.writerow(row)
    print(f"  eps {eps:g}  1/Fa {inv_fa:<8.6g} growth rate {row['growth_rate']:+.5f}  "
          f"({wall:.0f} s)", flush=True)
    return row


def bisect(eps, lo, hi, tol, extra, jobs=1):
    """Bisection on the sign of the growth rate, from the bracket [lo, hi] (moved until it
    holds a sign change); the members are kept on disk (summarise reads them). With jobs > 1
    the bracket's two ends run side by side, and each round runs `jobs` members that split the
    bracket into jobs + 1 equal parts (two members a round: a third of the bracket left)."""
    def rates(points):
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            return list(pool.map(lambda x: member(eps, x, extra)["growth_rate"], points))

    r_lo, r_hi = rates([lo, hi])
    widen = 0
    while not (r_lo < 0 < r_hi):  # move the bracket until it holds the onset
        widen += 1
        if widen > 4:
            sys.exit(f"eps {eps:g}: no sign change of the growth rate in [{lo:g}, {hi:g}]")
        width = hi - lo
        if r_lo >= 0:
            hi, lo = lo, max(lo - width, 0.05)
            r_hi, r_lo = r_lo, rates([lo])[0]
        else:
            lo, hi = hi, hi + width
            r_lo, r_hi = r_hi, rates([hi])[0]
    while hi - lo > 2 * tol + 1e-12:
        n = max(1, jobs)
        points = [lo + (hi - lo) * k / (n + 1) for k in range(1, n + 1)]
        # the rate grows with 1/Fa: the new bracket is the last decaying point and the
        # growing one next to it
        for x, r in zip(points, rates(points)):
            if r > 0:
                hi = x
                break
            lo = x


def summarise(eps, extra):
    """(result row or None, member rows) from the members of eps on disk: the bracket is
    the largest 1/Fa with a negative growth rate and the smallest above it with a positive
    one (what the bisection left)."""
    pattern = f"eps={eps:g}_beta={BETA:g}_activity=*"
    tag = member_tag(extra)
    members = sorted((read_member(d / "member.csv") for d in WORK.glob(pattern)
                      if (d / "member.csv").exists()
                      and d.name.endswith(tag) and "_" not in d.name.split("activity=")[1]
                      .removesuffix(tag)), key=lambda m: m["inv_fa"])
    decaying = [m for m in members if m["growth_rate"] < 0]
    if not decaying:
        return None, members
    low = max(decaying, key=lambda m: m["inv_fa"])
    growing = [m for m in members if m["growth_rate"] > 0 and m["inv_fa"] > low["inv_fa"]]
    if not growing:
        return None, members
    high = min(growing, key=lambda m: m["inv_fa"])
    lo, hi, r_lo, r_hi = low["inv_fa"], high["inv_fa"], low["growth_rate"], high["growth_rate"]
    return ({"beta": BETA, "epsilon": eps, "inv_fa_crit": 0.5 * (lo + hi), "bracket_lo": lo,
             "bracket_hi": hi, "inv_fa_zero_rate": lo + (hi - lo) * (-r_lo) / (r_hi - r_lo),
             "members": len(members),
             "wall_time_s": sum(m["wall_time_s"] for m in members)}, members)


def plot(results, members, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for eps in sorted({m["epsilon"] for m in members}, reverse=True):
        mine = sorted((m for m in members if m["epsilon"] == eps), key=lambda m: m["inv_fa"])
        ax1.plot([m["inv_fa"] for m in mine], [m["growth_rate"] for m in mine], "o-",
                 label=f"eps = {eps:g}")
    ax1.axhline(0, color="0.5", lw=0.8)
    ax1.set_xlabel("activity 1/Fa")
    ax1.set_ylabel("growth rate of |v_cell| (1/time)")
    ax1.set_title("Splay mode, fitted over t in [20, 50]", fontsize=10)
    ax1.legend()
    res = sorted(results, key=lambda r: r["epsilon"])
    ax2.errorbar([r["epsilon"] for r in res], [r["inv_fa_crit"] for r in res],
                 yerr=[0.5 * (r["bracket_hi"] - r["bracket_lo"]) for r in res], fmt="o-",
                 capsize=4, label="bisection (midpoint, half-width)")
    ax2.plot([0.21], [0.75], "s", color="0.3", label="thesis at eps 0.21")
    ax2.set_xlabel("eps")
    ax2.set_ylabel("critical activity 1/Fa_crit")
    ax2.set_title("Onset of motility, beta = 0 (thesis Fig. 6.10)", fontsize=10)
    ax2.set_xlim(0, max(0.45, max(r["epsilon"] for r in res) + 0.03))
    ax2.legend(fontsize=8)
    fig.savefig(path, dpi=120)


def write_results(results, members, tol, name, extra):
    write_csv(RESULTS / f"{name}.csv", COLUMNS, results)
    write_csv(RESULTS / f"{name}-members.csv", MEMBER_COLUMNS, members)
    lines = ["# Critical activity of the polar gel cell (thesis Fig. 6.10)", "",
             f"Written by `benchmarks/polar_critical.py`. beta = {BETA}, the cell of "
             "`benchmarks/studies/polar-bifurcation.yaml` (30 x 20 channel, splay seed 0.1), "
             "dt = 0.1 eps / 0.42" + "".join(f", {k} = {v}" for k, v in extra.items())
             + ". Each member runs to t = 50; its growth rate is the "
             f"least-squares slope of ln |v_cell| over t in [{WINDOW[0]:g}, {WINDOW[1]:g}]: "
             "positive means the splay mode grows (the cell starts to move). Bisection "
             f"on its sign to +-{tol:g}; the zero of the growth rate interpolated between "
             "the final bracket's ends is listed beside the midpoint.", "",
             "| eps | 1/Fa_crit | bracket | zero of the growth rate | members | wall s (1 core) |",
             "|---|---|---|---|---|---|"]
    for r in sorted(results, key=lambda r: -r["epsilon"]):
        lines.append(f"| {r['epsilon']:g} | {r['inv_fa_crit']:.3f} +- "
                     f"{0.5 * (r['bracket_hi'] - r['bracket_lo']):.3f} | "
                     f"({r['bracket_lo']:.4g}, {r['bracket_hi']:.4g}) | "
                     f"{r['inv_fa_zero_rate']:.3f} | {r['members']} | {r['wall_time_s']:.0f} |")
    lines += ["", "Members:", "", "| eps | 1/Fa | growth rate | dt | dofs | wall s |",
              "|---|---|---|---|---|---|"]
    for m in sorted(members, key=lambda m: (-m["epsilon"], m["inv_fa"])):
        lines.append(f"| {m['epsilon']:g} | {m['inv_fa']:.6g} | {m['growth_rate']:+.5f} | "
                     f"{m['dt']:.4g} | {int(m['dofs'])} | {m['wall_time_s']:.0f} |")
    lines += ["", "The thesis finds 1/Fa_crit ~ 0.75 at eps = 0.21 and a critical activity "
              "growing with eps (Fig. 6.10), in the channel [0, 160] x [0, 40] whose walls "
              "are 15 from the cell; the channel here (30 x 20, walls 5 from the cell, as in "
              "the bifurcation diagram `polar-bifurcation.md`) confines the flow that drives "
              "the splay mode. The rates agree with the diagram's long runs: there, at "
              "eps 0.42, |v_cell| decays at 1/Fa = 1 (by the factor e^-0.016 per time unit "
              "from t = 20 to 150) and grows at 1.5.", "", f"![growth rates and onset]({name}.png)", ""]
    write_report(RESULTS / f"{name}.md", lines)  # keeps the "## What it shows" section
    plot(results, members, RESULTS / f"{name}.png")


def committed_rows(path, epsilons):
    """Rows of a committed result file for the other epsilons (their members may no longer
    be on disk): a run for one eps adds to the tables instead of replacing them."""
    if not path.exists():
        return []
    with open(path) as f:
        rows = [{k: int(v) if k == "members" else float(v) for k, v in row.items()}
                for row in csv.DictReader(f)]
    return [r for r in rows if not any(abs(r["epsilon"] - e) < 1e-12 for e in epsilons)]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--epsilons", type=float, nargs="+", default=[0.42, 0.3])
    parser.add_argument("--bracket", type=float, nargs=2, default=[1.0, 1.5],
                        metavar=("LO", "HI"), help="first bracket of 1/Fa (moved if it does "
                        "not hold the onset)")
    parser.add_argument("--tolerance", type=float, default=0.02)
    parser.add_argument("--jobs", type=int, default=1,
                        help="members run side by side, one core each (default 1)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scene setting of every member (repeatable)")
    parser.add_argument("--name", default="polar-critical",
                        help="base name of the result files (default polar-critical)")
    parser.add_argument("--report-only", action="store_true",
                        help="write the results from the members already run")
    args = parser.parse_args(argv)
    extra = {}
    for item in args.set:
        key, sep, value = item.partition("=")
        if not sep or not key:
            sys.exit(f"--set {item!r}: expected KEY=VALUE")
        extra[key] = value
    if not args.report_only and not EXE.is_file():
        sys.exit(f"{EXE} not found: build first (cmake --build build)")
    results, members = [], []
    for eps in args.epsilons:
        if not args.report_only:
            print(f"eps {eps:g}: bisection in [{args.bracket[0]:g}, {args.bracket[1]:g}]",
                  flush=True)
            bisect(eps, *args.bracket, args.tolerance, extra, args.jobs)
        result, mine = summarise(eps, extra)
        members += mine
        if result is None:
            print(f"eps {eps:g}: no sign change among the {len(mine)} members run")
            continue
        results.append(result)
        print(f"eps {eps:g}: 1/Fa_crit = {result['inv_fa_crit']:.3f} +- "
              f"{0.5 * (result['bracket_hi'] - result['bracket_lo']):.3f} (zero of the "
              f"growth rate {result['inv_fa_zero_rate']:.3f})", flush=True)
    if results:
        results += committed_rows(RESULTS / f"{args.name}.csv", args.epsilons)
        members += committed_rows(RESULTS / f"{args.name}-members.csv", args.epsilons)
        write_results(results, members, args.tolerance, args.name, extra)
        print(f"written: {RESULTS / args.name}.csv, -members.csv, .md, .png")


if __name__ == "__main__":
    main()
