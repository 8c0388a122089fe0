"""numerics.stop_when_settled: a run towards a stationary state stops once the watched
observable has settled, with its final state written and checkpointed, and a restart
stops at the same step. The scene is test_checkpoint's ellipse under the Helfrich flow
with volume and area kept (helfrich_lagrange): its Helfrich energy falls from 4.73 to 4.0505
(measured to t = 0.3: 4.1169 at t = 0.02, 4.0513 at 0.16, 4.05053 at 0.3)."""
import pytest

from conftest import require_exe
from test_checkpoint import (assert_same_observables, cellphase, restart_from_shorter_run,
                             rows, vesicle_scene, write_scene)

import cellphase_results

WATCH = {"observable": "helfrich_energy", "over": 0.02, "relative": 3e-4}
END = 0.3


def settling_scene(end_time=END, **watch):
    """dt = 2^-10 (for 1e-3): the times of the steps are exact, so a run that ends at
    40 dt takes the steps of a longer run and a restart from its end continues that run
    bit for bit."""
    scene = vesicle_scene(end_time=end_time)
    scene["numerics"]["dt"] = 2.0**-10
    scene["numerics"]["stop_when_settled"] = {**WATCH, **watch}
    return scene


def varied(times, values, now, over):
    """max - min of the values over [now - over, now] (times within 1e-9 count as equal)."""
    window = [v for t, v in zip(times, values) if t >= now - over - 1e-9 and t <= now + 1e-9]
    return max(window) - min(window)


@pytest.fixture(scope="module")
def settled_run(tmp_path_factory):
    require_exe()
    work = tmp_path_factory.mktemp("settled")
    run_dir = work / "full"
    proc = cellphase(["run", write_scene(settling_scene(), work, run_dir)])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return {"rows": rows(run_dir), "dir": run_dir, "stdout": proc.stdout, "work": work}


def test_the_run_stops_at_the_first_step_where_the_window_has_settled(settled_run):
    r = settled_run["rows"]
    t = [float(x["time"]) for x in r]
    e = [float(x["helfrich_energy"]) for x in r]
    over, rel = WATCH["over"], WATCH["relative"]
    print(f"stopped at t = {t[-1]:g} (end_time {END}), energy {e[-1]:.6f}, varied "
          f"{varied(t, e, t[-1], over):.3e} over the last {over}")
    assert t[-1] < END - 0.05  # well before end_time
    assert "settled at step" in settled_run["stdout"] and "helfrich_energy varied by" in settled_run["stdout"]
    # The criterion, checked from the csv: met at the last row, not at any earlier row
    # with a full window.
    assert varied(t, e, t[-1], over) <= rel * abs(e[-1])
    for k in range(len(t) - 1):
        if t[k] >= over - 1e-9:
            assert varied(t, e, t[k], over) > rel * abs(e[k]), f"settled already at t = {t[k]}"


def test_the_settled_state_is_written_and_checkpointed(settled_run):
    last = settled_run["rows"][-1]
    frames = list(cellphase_results.read_fields(settled_run["dir"]))
    assert abs(frames[-1][0] - float(last["time"])) < 1e-12
    newest = sorted((settled_run["dir"] / "checkpoints").glob("checkpoint-*.cpk"))[-1]
    assert int(newest.stem.split("-")[1]) == int(last["step"])


def test_a_restart_restores_the_window_and_stops_at_the_same_step(tmp_path):
    # The shorter run ends at step 136, 8 steps before the run in one go settles (step 144):
    # without the rows before its checkpoint the restart would need 20 steps (over = 0.02)
    # to fill the window and would stop 12 steps late.
    full, continued, _ = restart_from_shorter_run(
        settling_scene(), settling_scene(end_time=136 * 2.0**-10), tmp_path)
    assert int(full[-1]["step"]) > 136
    print(f"in one go: {len(full)} rows; restarted: {len(continued)} rows")
    assert float(full[-1]["time"]) < END - 0.05
    assert_same_observables(full, continued)


@pytest.mark.parametrize("watch, message", [
    ({"observable": "speed_of_light"},
     'numerics.stop_when_settled.observable: found "speed_of_light", which is no column'),
    ({"over": 0.5}, "numerics.stop_when_settled.over: found 0.5, expected less than"),
    ({"relative": 0, "absolute": 0}, "both 0"),
    ({"relative": -1}, "numerics.stop_when_settled.relative"),
    ({"within": 1}, "within"),
])
def test_bad_settling_input_stops_before_the_first_step(tmp_path, watch, message):
    run_dir = tmp_path / "out"
    proc = cellphase(["run", write_scene(settling_scene(**watch), tmp_path, run_dir)])
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "error:" in proc.stderr and message in proc.stderr, proc.stderr
    csv_path = run_dir / "observables.csv"
    assert not csv_path.exists() or len(rows(run_dir)) <= 1  # nothing stepped


def test_check_states_the_settling_rule(tmp_path):
    path = write_scene(settling_scene(), tmp_path, tmp_path / "out")
    proc = cellphase(["check", path])
    assert proc.returncode == 0, proc.stderr
    assert ("stop when settled     helfrich_energy varies by at most max(0.0003 |value|, 0) "
            "over 0.02 time units (from t = 0.02)") in proc.stdout, proc.stdout
