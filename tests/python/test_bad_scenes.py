"""`cellphase check` rejects every malformed scene in tests/scenes/bad with a clear message.

Each line of tests/scenes/bad/expected.txt is `<file>: <text the message must contain>`.
The executable is taken from CELLPHASE_EXE (set by CTest).
"""
import os
import subprocess
from pathlib import Path

import pytest

EXE = os.environ.get("CELLPHASE_EXE")
if not EXE:
    pytest.skip("CELLPHASE_EXE is not set (run through ctest, or export it)",
                allow_module_level=True)

BAD = Path(__file__).resolve().parent.parent / "scenes" / "bad"
CRASH_MARKERS = ("Traceback", "terminate called", "Segmentation")


def expectations():
    cases = []
    for line in (BAD / "expected.txt").read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        name, expected = line.split(": ", 1)
        cases.append(pytest.param(name, expected, id=name))
    return cases


def check(path):
    return subprocess.run([EXE, "check", str(path)], capture_output=True, text=True,
                          timeout=60)


def assert_rejected(result, expected):
    assert result.returncode != 0, result.stdout
    for marker in CRASH_MARKERS:
        assert marker not in result.stderr, result.stderr
    assert expected in result.stderr, result.stderr


def test_expectations_cover_every_bad_scene():
    listed = {name for name, _ in (p.values for p in expectations())}
    present = {p.name for p in BAD.glob("*.yaml")}
    assert listed == present
    assert len(listed) >= 12


@pytest.mark.parametrize("name, expected", expectations())
def test_bad_scene_is_rejected(name, expected):
    result = check(BAD / name)
    assert_rejected(result, expected)
    assert result.returncode == 2
    assert result.stderr.startswith("error: ")


def test_missing_scene_file(tmp_path):
    result = check(tmp_path / "no-such-scene.yaml")
    assert_rejected(result, "cannot read scene file")
