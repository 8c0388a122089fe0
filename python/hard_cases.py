#!/usr/bin/python3
"""Run the hard-case suite (benchmarks/hard/*.yaml) and report how the scheme holds.

  hard_cases.py run [--bisect] [--only NAME ...]

For every case one status line: finished or not (exit status and first line of stderr),
the last time reached, max |phi|, the volume drift, whether the energy decayed
monotonically (all these models are passive), and with --bisect the largest stable time
step found by bisection. Failures are data: every case ends with its line. The table is
also written to benchmarks/results/hard-cases.md. See docs/studies.md.
"""
import argparse
import datetime
import math
import os
import platform
import shutil
import sys
from pathlib import Path

import numpy as np
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cellphase_results import ResultsError, read_observables  # noqa: E402
from study import find_executable, first_line, run_command  # noqa: E402
from study_file import StudyError, format_value  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
REGISTRY = ROOT / "benchmarks" / "hard"
WORK = ROOT / "output" / "hard-cases"
CASE_KEYS = {"description", "scene", "set", "energy", "bisect"}
BISECT_KEYS = {"dt", "steps", "halvings"}
PHI_BOUND = 1.5  # a run with max |phi| above this is counted unstable (phi lives in [-1, 1])


def load_case(path):
    """A registry entry: {description, scene (path), set, energy, bisect}."""
    try:
        case = yaml.safe_load(path.read_text())
    except yaml.YAMLError as e:
        raise StudyError(f"{path}: not valid YAML: {e}") from None
    if not isinstance(case, dict):
        raise StudyError(f"{path}: expected a mapping")
    unknown = sorted(set(case) - CASE_KEYS)
    if unknown:
        raise StudyError(f"{path}: unknown key {unknown[0]}; allowed: {', '.join(sorted(CASE_KEYS))}")
    if not isinstance(case.get("scene"), str):
        raise StudyError(f"{path}: scene: required (a path relative to the case file)")
    case["scene"] = (path.parent / case["scene"]).resolve()
    case.setdefault("set", {})
    case.setdefault("energy", "total_energy")
    bisect = case.setdefault("bisect", None)
    if bisect is not None:
        unknown = sorted(set(bisect) - BISECT_KEYS)
        if unknown:
            raise StudyError(f"{path}: unknown key bisect.{unknown[0]}; "
                             f"allowed: {', '.join(sorted(BISECT_KEYS))}")
        dts = bisect.get("dt")
        if not (isinstance(dts, list) and len(dts) == 2 and 0 < dts[0] < dts[1]):
            raise StudyError(f"{path}: bisect.dt: expected [stable dt, unstable dt], smaller first")
    case["name"] = path.stem
    return case


def run_case(exe, case, run_dir, overrides=None):
    """Run the case's scene with its overrides; return (exit status, message, obs or None)."""
    shutil.rmtree(run_dir, ignore_errors=True)
    run_dir.mkdir(parents=True)
    settings = {"output.every": 0, "output.progress": "false", **case["set"], **(overrides or {}),
                "output.directory": str(run_dir)}
    args = [exe, "run", str(case["scene"])]
    for key, value in settings.items():
        args += ["--set", f"{key}={format_value(value)}"]
    code, wall, _ = run_command(args, run_dir)
    try:
        obs = read_observables(run_dir)
    except ResultsError:
        obs = None
    message = "" if code == 0 else first_line(run_dir / "stderr.txt")
    return code, message, obs, wall


def measures(obs, energy_key):
    """Last time, max |phi|, volume drift and energy decay of a run's observables."""
    if obs is None or len(obs["time"]) == 0:
        return {}
    phi = max(np.max(np.abs(obs["phi_min"])), np.max(np.abs(obs["phi_max"])))
    volume = obs["volume"]
    drift = np.max(np.abs(volume - volume[0])) / abs(volume[0]) if volume[0] else math.nan
    energy = obs[energy_key]
    rises = np.diff(energy)
    # Relative to the energy scale, so round-off on a flat energy is not a rise.
    tol = 1e-10 * max(1.0, np.max(np.abs(energy)))
    worst = int(np.argmax(rises)) if len(rises) else 0
    decayed = "yes" if len(rises) == 0 or rises[worst] <= tol else \
        f"no (+{rises[worst]:.2e} at t={obs['time'][worst + 1]:.4g})"
    if not np.all(np.isfinite(energy)):
        decayed = "no (not finite)"
    # How far the centre of mass moved per unit time: a drift where the case is symmetric.
    centre = np.stack([obs.get(f"center_{a}", np.zeros_like(volume)) for a in "xyz"], axis=1)
    span = obs["time"][-1] - obs["time"][0]
    moved = float(np.linalg.norm(centre[-1] - centre[0]) / span) if span > 0 else 0.0
    return {"last_time": float(obs["time"][-1]), "max_phi": float(phi),
            "volume_drift": float(drift), "energy_decay": decayed, "centre_speed": moved}


def stable(exe, case, dt, steps, run_dir):
    """A run of `steps` steps of size dt is stable if it finishes and phi stays bounded."""
    code, _, obs, _ = run_case(exe, case, run_dir, {"numerics.dt": dt, "numerics.end_time": steps * dt})
    if code != 0 or obs is None:
        return False
    m = measures(obs, case["energy"])
    return math.isfinite(m["max_phi"]) and m["max_phi"] < PHI_BOUND


def largest_stable_dt(exe, case, run_dir):
    """Bisection (geometric: dt spans decades) between a stable and an unstable dt."""
    b = case["bisect"]
    lo, hi = b["dt"]
    # The same number of steps for every dt: each probe costs the same, and a large dt
    # is not judged on a single step.
    steps = b.get("steps", 20)
    if stable(exe, case, hi, steps, run_dir):
        return f">= {hi:.3g} (upper end stable)"
    if not stable(exe, case, lo, steps, run_dir):
        return f"< {lo:.3g} (lower end unstable)"
    for _ in range(b.get("halvings", 4)):
        mid = math.sqrt(lo * hi)
        if stable(exe, case, mid, steps, run_dir):
            lo = mid
        else:
            hi = mid
    return f"{lo:.3g} (unstable at {hi:.3g})"


def status_line(row):
    fields = [row["name"], row["status"]]
    if "last_time" in row:
        fields += [f"t_end {row['last_time']:.4g}", f"max|phi| {row['max_phi']:.4f}",
                   f"volume drift {row['volume_drift']:.2e}", f"energy decays {row['energy_decay']}",
                   f"centre speed {row['centre_speed']:.2e}"]
    if "dt_max" in row:
        fields.append(f"largest stable dt {row['dt_max']}")
    return ": ".join(fields[:2]) + ("; " + "; ".join(fields[2:]) if len(fields) > 2 else "")


def write_markdown(rows, path, bisect):
    head = ["case", "description", "status", "last time", "wall s", "max abs(phi)",
            "volume drift", "energy decays", "centre speed"] + (["largest stable dt"] if bisect else [])
    lines = ["# Hard cases", "",
             f"Generated by `python/hard_cases.py run{' --bisect' if bisect else ''}` on "
             f"{datetime.date.today()} on {platform.node()} ({os.cpu_count()} cores). "
             "Last time: the last row of observables.csv (the failure time when the run "
             f"failed). Volume drift: max |V - V0| / V0. Centre speed: |c(end) - c(0)| / time, a "
             "drift where the case is symmetric. Largest stable dt: bisection with "
             f"short runs (a fixed number of steps); stable means the run finishes with max |phi| < {PHI_BOUND}.", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [r["name"], r["description"], r["status"].replace("|", "/"),
                 f"{r['last_time']:.4g}" if "last_time" in r else "-", f"{r['wall']:.1f}",
                 f"{r['max_phi']:.4f}" if "max_phi" in r else "-",
                 f"{r['volume_drift']:.2e}" if "volume_drift" in r else "-",
                 r.get("energy_decay", "-"),
                 f"{r['centre_speed']:.2e}" if "centre_speed" in r else "-"]
        if bisect:
            cells.append(r.get("dt_max", "-"))
        lines.append("| " + " | ".join(cells) + " |")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")


def main(argv=None):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0].split("\n")[0],
        epilog=__doc__.split("\n\n", 1)[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    run_p = sub.add_parser("run", help="run every case and print one status line per case")
    run_p.add_argument("--bisect", action="store_true",
                       help="also find the largest stable dt of cases that have a bisect entry")
    run_p.add_argument("--only", nargs="+", metavar="NAME", help="run only these cases")
    run_p.add_argument("--registry", default=str(REGISTRY), help="folder of case files")
    run_p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "hard-cases.md"),
                       help="markdown report (default benchmarks/results/hard-cases.md)")
    run_p.add_argument("--exe", help="cellphase executable (default: $CELLPHASE_EXE, "
                                     "else build/cellphase)")
    a = parser.parse_args(argv)
    try:
        exe = find_executable(a.exe)
        paths = sorted(Path(a.registry).glob("*.yaml"))
        if a.only:
            missing = set(a.only) - {p.stem for p in paths}
            if missing:
                raise StudyError(f"no case {', '.join(sorted(missing))} in {a.registry}")
            paths = [p for p in paths if p.stem in a.only]
        cases = [load_case(p) for p in paths]
    except StudyError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    rows = []
    for case in cases:
        run_dir = WORK / case["name"]
        code, message, obs, wall = run_case(exe, case, run_dir)
        row = {"name": case["name"], "description": case.get("description", ""), "wall": wall,
               "status": "finished" if code == 0 else f"FAILED (exit {code}) {message}"}
        try:
            row.update(measures(obs, case["energy"]))
        except KeyError as e:
            row["status"] += f" (no column {e} in observables.csv)"
        if a.bisect and case["bisect"]:
            row["dt_max"] = largest_stable_dt(exe, case, WORK / (case["name"] + "-bisect"))
        rows.append(row)
        print(status_line(row), flush=True)
    write_markdown(rows, Path(a.out), a.bisect)
    print(f"report: {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
