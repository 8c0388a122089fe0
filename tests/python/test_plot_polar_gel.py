"""python/plot_polar_gel.py on a real (short) active polar gel run: the figures of
Figs. 6.5-6.7 are written with one column per requested time, the frames chosen are the
nearest output times, and a run without the gel's fields is refused with a message."""
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import run_scene
from test_polar_gel import gel_scene

plt = pytest.importorskip("matplotlib.pyplot")

PYTHON_DIR = Path(__file__).resolve().parents[2] / "python"
SCRIPT = PYTHON_DIR / "plot_polar_gel.py"
sys.path.insert(0, str(PYTHON_DIR))
import plot_polar_gel  # noqa: E402


def plot(*args):
    return subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def gel_run(tmp_path_factory):
    """Ten steps of an active gel (1/Fa = 2) with phi, P and v written every 5 steps."""
    work = tmp_path_factory.mktemp("gel")
    scene = gel_scene(activity=2.0, dt=0.02, end_time=0.2, initial={"noise": 0.05, "seed": 3})
    scene["output"] = {"every": 5, "fields": ["phi", "P", "v"]}
    run_scene(scene, work)
    return work / "out"


def test_figures_have_one_column_per_time_and_the_motion_panels(gel_run):
    result = plot(gel_run, "--times", 0, 0.2)
    assert result.returncode == 0, result.stderr
    two = plt.imread(gel_run / "polar-gel.png")
    result = plot(gel_run, "--times", 0, 0.1, 0.2)
    assert result.returncode == 0, result.stderr
    three = plt.imread(gel_run / "polar-gel.png")
    # Three rows (|P|, v in the laboratory frame, v in the co-moving frame) of equal height;
    # the width grows with the columns (3.2 in per column at 110 dpi).
    assert two.shape[0] == three.shape[0]
    assert abs((three.shape[1] - two.shape[1]) - 3.2 * 110) <= 2
    motion = plt.imread(gel_run / "polar-motion.png")
    assert motion.shape[0] > 200 and motion.shape[1] > 200
    # The image is not blank: the fields and panels cover a good part of it.
    assert three[..., :3].std() > 0.05


def test_frames_are_the_nearest_output_times(gel_run):
    frames = plot_polar_gel.nearest_frames(gel_run, [0.04, 0.16])
    assert [round(f[0], 6) for f in frames] == [0.0, 0.2]
    _, points, cells, values = frames[1]
    assert set(values) >= {"phi", "P", "v"}
    assert len(values["P"]) == len(points) and cells.shape[1] == 3


def test_a_run_without_the_gel_fields_is_refused(gel_run, tmp_path):
    missing = plot(tmp_path)
    assert missing.returncode != 0 and "no observables.csv" in missing.stderr
    # A run that wrote phi only: the message names the fields and the keys that write them.
    work = tmp_path / "phi_only"
    work.mkdir()
    scene = gel_scene(activity=0.0, dt=0.02, end_time=0.04)
    scene["output"] = {"every": 1, "fields": ["phi"]}
    run_scene(scene, work)
    result = plot(work / "out")
    assert result.returncode != 0
    assert "phi, P and v" in result.stderr and "output.fields" in result.stderr
