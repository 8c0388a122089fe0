"""Error norms, orders of convergence and the markdown/PNG reports of a study.

A member's result is a dict:
    {"name": str, "eps": float or None, "params": {key: value},
     "obs": {column: array} or None (no observables.csv),
     "status": "ok" or a failure text, "wall": seconds or None, "peak_mb": MB or None}
"""
import math
from pathlib import Path

import numpy as np

import matplotlib
import matplotlib.ticker
matplotlib.use("Agg")  # reports are written without a display
import matplotlib.pyplot as plt  # noqa: E402


def error_norm(ref_time, ref_q, time, q):
    """Relative error ||e||_2 of thesis section 5.3: sqrt(sum |q_ref - q|^2 / sum |q_ref|^2)
    over the output times of the member, the reference interpolated linearly in time."""
    ref_at = np.interp(np.asarray(time, float), np.asarray(ref_time, float),
                       np.asarray(ref_q, float))
    den = np.sum(ref_at ** 2)
    if den == 0:
        return math.nan
    return float(np.sqrt(np.sum((ref_at - np.asarray(q, float)) ** 2) / den))


def rate_of_convergence(e_coarse, e_fine, eps_coarse, eps_fine):
    """ROC = log(e_i / e_{i+1}) / log(eps_i / eps_{i+1}); nan if an error is not positive."""
    if not (e_coarse > 0 and e_fine > 0) or eps_coarse == eps_fine:
        return math.nan
    return math.log(e_coarse / e_fine) / math.log(eps_coarse / eps_fine)


def _fmt(value, spec):
    return "-" if value is None or (isinstance(value, float) and math.isnan(value)) \
        else format(value, spec)


def _cost_cells(r):
    obs = r["obs"]
    dofs = int(obs["dofs"][-1]) if obs is not None and len(obs["time"]) else None
    steps = len(obs["time"]) - 1 if obs is not None else None  # first row is the initial state
    return [_fmt(dofs, "d"), _fmt(steps, "d"), _fmt(r["wall"], ".1f"), _fmt(r["peak_mb"], ".0f")]


def convergence_errors(results, observables):
    """{observable: [(error, roc) per member except the reference]} against the last
    (finest) member; members without observables get nan."""
    ref = results[-1]["obs"]
    table = {}
    for key in observables:
        rows, prev = [], None
        for r in results[:-1]:
            e = math.nan
            if ref is not None and r["obs"] is not None and r["status"] == "ok":
                e = error_norm(ref["time"], ref[key], r["obs"]["time"], r["obs"][key])
            roc = rate_of_convergence(prev[0], e, prev[1], r["eps"]) if prev else math.nan
            rows.append((e, roc))
            prev = (e, r["eps"])
        table[key] = rows
    return table


def write_convergence_report(out_dir, title, results, observables, preamble=""):
    """report.md (Table 5.2 style, with cost columns) and error_vs_walltime.png."""
    out_dir = Path(out_dir)
    results = sorted(results, key=lambda r: -r["eps"])  # coarsest first, reference last
    ref = results[-1]
    missing = [k for k in observables if ref["obs"] is not None and k not in ref["obs"]]
    if missing:
        raise ValueError(f"observables not in observables.csv: {', '.join(missing)}")
    errors = convergence_errors(results, observables) if ref["status"] == "ok" else None
    head = ["eps", "DOFs", "steps", "wall s", "peak MB"]
    for k in observables:
        head += [f"{k} \\|\\|e\\|\\|_2", "ROC"]
    lines = [f"# {title}", "", preamble, "",
             "Relative error norm ||e||_2 of each observable's time series against the finest "
             "member (the reference, interpolated linearly in time), and the order of "
             "convergence ROC = log(e_i/e_(i+1)) / log(eps_i/eps_(i+1)) between neighbours. "
             "DOFs at the last step; wall time and peak memory (largest resident set) of "
             "the run as measured by the study runner.", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for i, r in enumerate(results):
        cells = [f"{r['eps']:.4g}"] + _cost_cells(r)
        if r is ref:
            note = "reference" if r["status"] == "ok" else r["status"]
            cells += [note] + [""] * (2 * len(observables) - 1)
        elif r["status"] != "ok":
            cells += [r["status"]] + [""] * (2 * len(observables) - 1)
        elif errors is None:
            cells += ["no reference"] + [""] * (2 * len(observables) - 1)
        else:
            for k in observables:
                e, roc = errors[k][i]
                cells += [_fmt(e, ".3e"), _fmt(roc, ".2f")]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "![error against wall time](error_vs_walltime.png)", ""]
    (out_dir / "report.md").write_text("\n".join(lines))

    fig, axes = plt.subplots(1, len(observables), figsize=(3.6 * len(observables), 3.4),
                             squeeze=False)
    for ax, k in zip(axes[0], observables):
        points = [(r["wall"], errors[k][i][0], r["eps"]) for i, r in enumerate(results[:-1])
                  if errors is not None and r["wall"] and errors[k][i][0] > 0]
        if points:
            walls, errs, eps = zip(*points)
            ax.loglog(walls, errs, "o-")
            # Ticks at the members' wall times: log minor labels overlap on narrow ranges.
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.set_xticks(walls, [f"{w:.3g}" for w in walls])
            for w, e, x in points:
                ax.annotate(f"eps={x:.3g}", (w, e), fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        else:
            ax.text(0.5, 0.5, "no errors", ha="center", transform=ax.transAxes)
        ax.set_title(k, fontsize=9)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("||e||_2")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out_dir / "error_vs_walltime.png", dpi=110)
    plt.close(fig)


def end_state(r, key):
    """Value of `key` at the last output of a member (nan when it has none)."""
    obs = r["obs"]
    if obs is None or key not in obs or len(obs[key]) == 0:
        return math.nan
    return float(obs[key][-1])


def _axis_value(v):
    """Numbers are plotted as numbers, names (e.g. a linearisation) as category labels."""
    return v if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v)


def write_sweep_report(out_dir, title, results, keys, quantities, preamble=""):
    """report.md (one row per member) and end_state.png (each quantity against the first
    varied key, one line per combination of the other keys)."""
    out_dir = Path(out_dir)
    head = list(keys) + ["status", "end time", "steps", "wall s", "peak MB"] + list(quantities)
    lines = [f"# {title}", "", preamble, "",
             "End-state quantities (last row of observables.csv) of every member.", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in results:
        obs = r["obs"]
        cells = [str(r["params"][k]) for k in keys] + [
            r["status"], _fmt(end_state(r, "time"), ".4g"),
            _fmt(len(obs["time"]) - 1 if obs is not None else None, "d"),
            _fmt(r["wall"], ".1f"), _fmt(r["peak_mb"], ".0f")]
        cells += [_fmt(end_state(r, q), ".5g") for q in quantities]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "![end state against the varied parameter](end_state.png)", ""]
    (out_dir / "report.md").write_text("\n".join(lines))

    x_key, others = keys[0], keys[1:]
    groups = {}
    for r in results:
        groups.setdefault(tuple(r["params"][k] for k in others), []).append(r)
    fig, axes = plt.subplots(1, len(quantities), figsize=(3.6 * len(quantities), 3.4),
                             squeeze=False)
    for ax, q in zip(axes[0], quantities):
        for label, group in groups.items():
            xs = [_axis_value(r["params"][x_key]) for r in group]
            ys = [end_state(r, q) for r in group]
            name = ", ".join(f"{k}={v}" for k, v in zip(others, label)) or None
            ax.plot(xs, ys, "o-", label=name)
            # Failed members are marked where they would be: failures are part of the diagram.
            for x, r in zip(xs, group):
                if r["status"] != "ok":
                    ax.axvline(x, color="red", alpha=0.3, lw=4)
        ax.set_title(q, fontsize=9)
        ax.set_xlabel(x_key)
        ax.grid(True, alpha=0.3)
        if others:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out_dir / "end_state.png", dpi=110)
    plt.close(fig)
