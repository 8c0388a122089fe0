"""Every demo scene (cut to a few steps with remeshes and checkpoints, tests/regression/
cases.py) gives the observables recorded before the modular core replaced the hand-wired
time loop: the sub-problems do the same arithmetic in the same order.

The comparison was bitwise, which holds only where they were recorded: on this AMD EPYC
machine the program that recorded them (c96921f, which passed this test in CI before)
differs in the last bit from step 0 on. Forcing OpenBLAS's core type or masking glibc's FMA
and AVX2 code paths did not restore the bits; the cause is not pinned down. So each value
must agree to 1e-11 of max(1, |value|): measured here, at most 1.6e-12 (the stabilised
vesicle's energy, which its multiplier moves), 5e-14 elsewhere. Two ill-conditioned columns
get 1e-8: the inclination of a near-round cell (the axis of a nearly isotropic moment
tensor, 1.2e-9 degrees apart) and the multipliers (lambda_area 4e-10)."""
import os
import sys
import pathlib

import pytest

from conftest import EXE, require_exe

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "regression"))
import cases  # noqa: E402

HERE = pathlib.Path(cases.__file__).resolve().parent


@pytest.mark.parametrize("name", sorted(cases.cases()))
def test_observables_as_recorded(tmp_path, name):
    require_exe()
    out = cases.run_case(EXE, cases.cases()[name], tmp_path / name)
    got = cases.physics_columns(out)
    want = cases.physics_columns(HERE / f"{name}.csv")
    assert len(got) == len(want), f"{len(got)} rows, recorded {len(want)}"
    for g, w in zip(got, want):
        diff = {k: (g.get(k), v) for k, v in w.items() if not agrees(k, g.get(k), v)}
        assert not diff, f"step {w['step']}: columns differ (got, recorded): {diff}"


def agrees(column, got, recorded):
    if got == recorded:
        return True
    try:
        a, b = float(got), float(recorded)
    except (TypeError, ValueError):
        return False
    name = column.rsplit(".", 1)[-1]  # per-cell columns: <cell>.<name>
    ill_conditioned = name == "inclination_deg" or name.startswith("lambda_")
    return abs(a - b) <= (1e-8 if ill_conditioned else 1e-11) * max(1.0, abs(b))
