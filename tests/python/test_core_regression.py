"""Every demo scene (cut to a few steps with remeshes and checkpoints, tests/regression/
cases.py) gives bitwise the observables recorded before the modular core replaced the
hand-wired time loop: the sub-problems do the same arithmetic in the same order."""
import os
import sys
import pathlib

import pytest

from conftest import EXE, require_exe

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "regression"))
import cases  # noqa: E402

HERE = pathlib.Path(cases.__file__).resolve().parent


@pytest.mark.parametrize("name", sorted(cases.cases()))
def test_observables_bitwise_as_recorded(tmp_path, name):
    require_exe()
    out = cases.run_case(EXE, cases.cases()[name], tmp_path / name)
    got = cases.physics_columns(out)
    want = cases.physics_columns(HERE / f"{name}.csv")
    assert len(got) == len(want), f"{len(got)} rows, recorded {len(want)}"
    for g, w in zip(got, want):
        diff = {k: (g.get(k), v) for k, v in w.items() if g.get(k) != v}
        assert not diff, f"step {w['step']}: columns differ (got, recorded): {diff}"
