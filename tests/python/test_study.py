"""Studies: error norm and ROC on synthetic series, study-file checks, reports, and a tiny
convergence study run end to end through the real executable."""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import EXE, require_exe

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
from study_file import StudyError, load_study  # noqa: E402
from study_report import (error_norm, rate_of_convergence, write_convergence_report,  # noqa: E402
                          write_sweep_report)

STUDY = ROOT / "python" / "study.py"
AC_SCENE = ROOT / "demos" / "allen-cahn-circle" / "scene.yaml"


def synthetic_result(eps, obs, **extra):
    return {"name": f"eps{eps}", "eps": eps, "params": {}, "obs": obs, "status": "ok",
            "wall": 1.0 / eps, "peak_mb": 50.0, **extra}


def test_error_norm_constant_offset():
    t = np.linspace(0, 1, 11)
    # q = 1.1 against q_ref = 1 everywhere: ||e|| = sqrt(n 0.01 / n) = 0.1.
    assert error_norm(t, np.ones_like(t), t, 1.1 * np.ones_like(t)) == pytest.approx(0.1)


def test_error_norm_interpolates_reference_in_time():
    # A linear reference on a fine time grid is matched exactly at the member's (other) times.
    ref_t = np.linspace(0, 1, 101)
    t = np.array([0.0, 0.123, 0.5, 0.77, 1.0])
    assert error_norm(ref_t, 2 + 3 * ref_t, t, 2 + 3 * t) == pytest.approx(0, abs=1e-14)
    # A reference known only at t = 0 and 1 is interpolated: at t = 0.5 it is 2, not 0.
    e = error_norm([0, 1], [1, 3], [0.5], [1.0])
    assert e == pytest.approx(0.5)  # |2 - 1| / |2|


@pytest.mark.parametrize("order", [1, 2, 3])
def test_roc_of_exact_power_law(order):
    # q = 1 + c eps^p with the reference at eps = 0: e(eps) = c eps^p / 1 exactly, ROC = p.
    eps = [0.064, 0.0457, 0.032]
    e = [0.3 * x ** order for x in eps]
    for a, b, ea, eb in zip(eps, eps[1:], e, e[1:]):
        assert rate_of_convergence(ea, eb, a, b) == pytest.approx(order)
    assert math.isnan(rate_of_convergence(0.0, 1e-3, 0.1, 0.05))


def test_convergence_report_on_exact_ladder(tmp_path):
    # q(t) = 1 + eps^2 t with a reference at eps = 1e-6 (q_ref = 1 to 1e-12): ROC 2.
    t = np.linspace(0, 1, 21)
    results = [synthetic_result(eps, {"time": t, "dofs": np.full_like(t, 100 / eps),
                                      "q": 1 + eps ** 2 * t})
               for eps in (1e-6, 0.08, 0.04, 0.02)]  # given in any order: sorted by eps
    write_convergence_report(tmp_path, "synthetic", results, ["q"])
    text = (tmp_path / "report.md").read_text()
    rows = [ln for ln in text.splitlines() if ln.startswith("| 0.0")]
    assert len(rows) == 3 and all("2.00" in r for r in rows[1:]), text
    assert "reference" in text
    assert (tmp_path / "error_vs_walltime.png").stat().st_size > 1000


def test_sweep_report_on_synthetic_results(tmp_path):
    t = np.linspace(0, 1, 5)
    results = []
    for mobility in (1, 5, 10):
        for kind in ("taylor", "stabilised"):
            results.append({"name": f"m{mobility}{kind}", "eps": None, "status": "ok",
                            "params": {"phase_field.mobility": mobility,
                                       "numerics.linearisation": kind},
                            "obs": {"time": t, "circularity": 0.5 + 0.01 * mobility * t},
                            "wall": 1.0, "peak_mb": 40.0})
    results[-1].update(status="failed (exit 3): diverged", obs=None)
    keys = ["phase_field.mobility", "numerics.linearisation"]
    write_sweep_report(tmp_path, "synthetic sweep", results, keys, ["circularity"])
    text = (tmp_path / "report.md").read_text()
    assert "| 5 | taylor | ok | 1 | 4 | 1.0 | 40 | 0.55 |" in text, text
    assert "failed (exit 3): diverged" in text
    assert (tmp_path / "end_state.png").stat().st_size > 1000


def write_study(tmp_path, text):
    path = tmp_path / "study.yaml"
    path.write_text(text.replace("SCENE", str(AC_SCENE)))
    return path


@pytest.mark.parametrize("text, message", [
    ("scene: SCENE\noutput: o\nsweep: {a: [1]}\nrepeat: 3\n", "unknown key repeat"),
    ("scene: SCENE\noutput: o\nladder: {epsilon: [0.1, 0.05], rulez: {}}\n", "ladder.rulez"),
    ("scene: SCENE\noutput: o\nladder: {epsilon: [0.05, 0.1], rules: "
     "{resolution_times_epsilon: 1, dt_over_epsilon: 0.1}}\n", "must decrease"),
    ("scene: SCENE\noutput: o\nladder: {epsilon: [0.1, 0.05], rules: "
     "{resolution_times_epsilon: 1}}\n", "ladder.rules.dt_over_epsilon: required"),
    ("scene: SCENE\noutput: o\nladder: {epsilon: [0.1, 0.05], rules: {resolution_times_epsilon: "
     "1, base_cell_over_epsilon: 2, dt_over_epsilon: 0.1}}\n", "exactly one of base_cell_over"),
    ("scene: SCENE\noutput: o\nladder: {epsilon: [0.1, x], rules: {}}\n", "'x' is not a positive"),
    ("scene: SCENE\noutput: o\nsweep: {a: 3}\n", "sweep.a: expected a non-empty list"),
    ("scene: SCENE\noutput: o\n", "exactly one of ladder"),
    ("scene: nowhere.yaml\noutput: o\nsweep: {a: [1]}\n", "nowhere.yaml: no such file"),
    ("scene: SCENE\noutput: o\nsweep: {a: [1]}\nreport: {end: [x]}\n", "unknown key report.end"),
    ("scene: SCENE\noutput: o\nsweep: {'a, b': [[1, 2], [3]]}\n", "list of 2 values, one per key"),
    ("scene: SCENE\noutput: o\nsweep: {'a, b': [[1, 2]], a: [4]}\n", "varied twice"),
])
def test_study_file_errors_name_the_key(tmp_path, text, message):
    with pytest.raises(StudyError, match=message.replace("(", r"\(")):
        load_study(write_study(tmp_path, text))


def test_ladder_rules_scale_resolution_and_dt(tmp_path):
    study = load_study(write_study(tmp_path, (
        "scene: SCENE\noutput: o\nset: {numerics.end_time: 0.1}\n"
        "ladder: {epsilon: [0.064, 0.032], rules: "
        "{resolution_times_epsilon: 0.64, dt_over_epsilon: 0.05}}\n")))
    coarse, fine = study.members
    assert coarse.overrides["domain.resolution"] == [10, 10]
    assert fine.overrides["domain.resolution"] == [20, 20]
    assert fine.overrides["numerics.dt"] == pytest.approx(0.0016)
    assert coarse.overrides["numerics.end_time"] == 0.1
    assert study.output == tmp_path / "o"


def test_ladder_base_cell_rule_keeps_cells_square_on_a_long_domain(tmp_path):
    """base_cell_over_epsilon: the base cell size h = c eps on every axis of a 4 x 1 channel
    (the polar-gel cell's, thesis section 6.2.5), after the study's own domain.upper."""
    study = load_study(write_study(tmp_path, (
        "scene: SCENE\noutput: o\nset: {domain.lower: [0, 0], domain.upper: [160, 40]}\n"
        "ladder: {epsilon: [0.3, 0.15], rules: "
        "{base_cell_over_epsilon: 10, dt_over_epsilon: 0.5}}\n")))
    coarse, fine = study.members
    assert coarse.overrides["domain.resolution"] == [53, 13]  # h = 3: 160/3, 40/3 rounded
    assert fine.overrides["domain.resolution"] == [107, 27]   # h = 1.5
    assert fine.overrides["numerics.dt"] == pytest.approx(0.075)


def test_keys_joined_by_a_comma_vary_together(tmp_path):
    """Be and the mobility gamma = 0.01 Be (Table 5.1) change together: 2 x 2 members, not 8."""
    study = load_study(write_study(tmp_path, (
        "scene: SCENE\noutput: o\nsweep:\n"
        "  numbers.Be, phase_field.mobility: [[6.6, 0.066], [66, 0.66]]\n"
        "  numbers.Ca: [0.264, 1.32]\n")))
    assert [m.name for m in study.members] == [
        "Be=6.6_mobility=0.066_Ca=0.264", "Be=6.6_mobility=0.066_Ca=1.32",
        "Be=66_mobility=0.66_Ca=0.264", "Be=66_mobility=0.66_Ca=1.32"]
    assert study.members[2].overrides == {"numbers.Be": 66, "phase_field.mobility": 0.66,
                                          "numbers.Ca": 0.264}
    assert study.sweep_keys == ["numbers.Be", "phase_field.mobility", "numbers.Ca"]


def test_study_cli_rejects_unknown_key_with_exit_2(tmp_path):
    path = write_study(tmp_path, "scene: SCENE\noutput: o\nsweep: {a: [1]}\nbogus: 1\n")
    proc = subprocess.run([sys.executable, str(STUDY), "report", str(path)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert "unknown key bogus" in proc.stderr and "Traceback" not in proc.stderr


def test_tiny_convergence_study_end_to_end(tmp_path):
    require_exe()
    path = write_study(tmp_path, (
        "scene: SCENE\noutput: out\n"
        "set: {numerics.end_time: 0.01, numerics.mesh.remesh_every: 0}\n"
        "ladder: {epsilon: [0.16, 0.113, 0.08], rules: "
        "{resolution_times_epsilon: 0.48, dt_over_epsilon: 0.05}}\n"
        "observables: [volume, surface]\n"))
    env = {**os.environ, "CELLPHASE_EXE": EXE}
    run = [sys.executable, str(STUDY), "run", str(path), "--jobs", "2"]
    proc = subprocess.run(run, capture_output=True, text=True, env=env, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    report = (tmp_path / "out" / "report.md").read_text()
    assert "| 0.08 |" in report and "reference" in report
    assert report.count("e-0") >= 4, report  # two errors for each of the two coarse members
    assert (tmp_path / "out" / "error_vs_walltime.png").stat().st_size > 1000
    # A second run skips the finished members.
    proc = subprocess.run(run, capture_output=True, text=True, env=env, timeout=60)
    assert proc.stdout.count("skipped") == 3, proc.stdout
    # Other settings for every member: none of the old results is reused.
    path.write_text(path.read_text().replace("remesh_every: 0", "remesh_every: 1"))
    proc = subprocess.run(run, capture_output=True, text=True, env=env, timeout=60)
    assert proc.returncode == 0 and proc.stdout.count("finished") == 3, proc.stdout


def test_archived_members_are_restored_in_a_new_checkout(tmp_path):
    # A study run in one place, archived, and restored where its output directory is empty
    # (a new machine): every member is skipped and the report gives the same errors.
    require_exe()
    from study_archive import archive_members, restore_members
    text = ("scene: SCENE\noutput: out\n"
            "set: {numerics.end_time: 0.01, numerics.mesh.remesh_every: 0}\n"
            "ladder: {epsilon: [0.16, 0.113, 0.08], rules: "
            "{resolution_times_epsilon: 0.48, dt_over_epsilon: 0.05}}\n"
            "observables: [volume, surface]\nreport: {end_state: [circularity]}\n")
    first, second = tmp_path / "first", tmp_path / "second"
    first.mkdir(), second.mkdir()
    env = {**os.environ, "CELLPHASE_EXE": EXE}
    run = [sys.executable, str(STUDY), "run"]
    proc = subprocess.run(run + [str(write_study(first, text))], capture_output=True, text=True,
                          env=env, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    archive = tmp_path / "archive"
    assert archive_members(load_study(first / "study.yaml"), archive) == \
        ["eps0.16", "eps0.113", "eps0.08"]
    header = (archive / "eps0.08.csv").read_text().splitlines()[0].split(",")
    assert {"time", "step", "dofs", "volume", "surface", "circularity", "wall_solve"} <= set(header)
    assert "output.directory" not in (archive / "eps0.08.json").read_text()

    path = write_study(second, text)
    assert restore_members(load_study(path), archive) == (["eps0.16", "eps0.113", "eps0.08"], [])
    proc = subprocess.run(run + [str(path)], capture_output=True, text=True, env=env, timeout=60)
    assert proc.returncode == 0 and proc.stdout.count("skipped") == 3, proc.stdout
    # Archiving the restored members again changes nothing in the archive.
    before = {f.name: f.read_text() for f in archive.iterdir()}
    archive_members(load_study(path), archive)
    assert {f.name: f.read_text() for f in archive.iterdir()} == before
    table = [ln for ln in (first / "out" / "report.md").read_text().splitlines() if "| 0.1" in ln]
    again = [ln for ln in (second / "out" / "report.md").read_text().splitlines() if "| 0.1" in ln]
    # The same errors and ROC (the wall time and peak memory columns come from the archive).
    assert [ln.split("|")[6:] for ln in table] == [ln.split("|")[6:] for ln in again]

    # An archive made with other settings is not restored into an edited study.
    edited = tmp_path / "edited"
    edited.mkdir()
    path = write_study(edited, text.replace("remesh_every: 0", "remesh_every: 1"))
    restored, skipped = restore_members(load_study(path), archive)
    assert restored == [] and [name for name, _ in skipped] == ["eps0.16", "eps0.113", "eps0.08"]


def test_progress_of_a_running_member(tmp_path):
    # The watch reads the last whole row of a growing observables.csv (a half-written last
    # line is ignored), gives the share of the end time and, from the second reading, the
    # time left at the pace between the readings.
    from study_progress import ProgressWatch, duration, member_end_time
    obs = tmp_path / "observables.csv"
    watch = ProgressWatch(interval=0)
    watch.started("eps0.1", tmp_path, end_time=2.0)
    assert "starting" in watch.lines()[0]
    obs.write_text("step,time,volume\n0,0,1\n1,0.5,1\n2,0.7")
    first = watch.lines()[0]
    assert "t = 0.5 of 2 (25 %)" in first and "left" not in first
    obs.write_text("step,time,volume\n0,0,1\n1,0.5,1\n2,1,1\n3,1.2")
    second = watch.lines()[0]
    assert "t = 1 of 2 (50 %)" in second and "left" in second, second
    watch.finished("eps0.1")
    assert watch.lines() == []
    assert duration(42) == "42 s" and duration(125) == "2 min 05 s" and duration(3 * 3600 + 60) == "3 h 01 min"
    assert member_end_time(AC_SCENE, {"numerics.end_time": 0.25}) == 0.25
    assert member_end_time(AC_SCENE, {}) > 0  # the scene's own
    assert member_end_time(tmp_path / "missing.yaml", {}) is None


def test_hard_case_registry_loads_and_measures():
    import hard_cases
    cases = [hard_cases.load_case(p) for p in sorted(hard_cases.REGISTRY.glob("*.yaml"))]
    assert len(cases) >= 5 and all(c["scene"].is_file() for c in cases)
    t = np.array([0.0, 0.1, 0.2, 0.3])
    obs = {"time": t, "phi_min": np.array([-1, -1, -1.2, -1.0]), "phi_max": np.ones(4),
           "volume": np.array([2.0, 2.0, 2.1, 1.9]), "total_energy": np.array([3, 2, 2.5, 1.0])}
    m = hard_cases.measures(obs, "total_energy")
    assert m["max_phi"] == pytest.approx(1.2)
    assert m["volume_drift"] == pytest.approx(0.05)
    assert m["energy_decay"].startswith("no (+5.00e-01 at t=0.2")
    obs["total_energy"] = np.array([3, 2, 1.5, 1.0])
    assert hard_cases.measures(obs, "total_energy")["energy_decay"] == "yes"


def test_hard_case_unknown_key(tmp_path):
    import hard_cases
    path = tmp_path / "case.yaml"
    path.write_text(f"scene: {AC_SCENE}\nsett: {{}}\n")
    with pytest.raises(StudyError, match="unknown key sett"):
        hard_cases.load_case(path)


def test_failures_are_data(tmp_path):
    # A member and a hard case the executable rejects: status lines and reports, no traceback.
    require_exe()
    env = {**os.environ, "CELLPHASE_EXE": EXE}
    path = write_study(tmp_path, "scene: SCENE\noutput: out\nset: {numerics.end_time: 0.004}\n"
                                 "sweep: {numerics.epsilon: [-1, 0.1]}\n")
    proc = subprocess.run([sys.executable, str(STUDY), "run", str(path)], capture_output=True,
                          text=True, env=env, timeout=60)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    report = (tmp_path / "out" / "report.md").read_text()
    assert "| -1 | failed (exit 2): error:" in report and "| 0.1 | ok |" in report, report

    registry = tmp_path / "hard"
    registry.mkdir()
    (registry / "bad.yaml").write_text(f"scene: {AC_SCENE}\nset: {{numerics.epsilon: -1}}\n")
    proc = subprocess.run([sys.executable, str(ROOT / "python" / "hard_cases.py"), "run",
                           "--registry", str(registry), "--out", str(tmp_path / "hard.md")],
                          capture_output=True, text=True, env=env, timeout=60)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stdout.startswith("bad: FAILED (exit 2) error:"), proc.stdout
    assert "FAILED (exit 2)" in (tmp_path / "hard.md").read_text()


def test_an_executable_that_cannot_start_fails_the_member_not_the_study(tmp_path):
    # As when the build replaces it while a study runs: a failed member, run again next time.
    broken = tmp_path / "cellphase"
    broken.write_text("not a program\n")
    broken.chmod(0o644)
    env = {**os.environ, "CELLPHASE_EXE": str(broken)}
    path = write_study(tmp_path, "scene: SCENE\noutput: out\nset: {numerics.end_time: 0.004}\n"
                                 "sweep: {numerics.epsilon: [0.1]}\n")
    proc = subprocess.run([sys.executable, str(STUDY), "run", str(path)], capture_output=True,
                          text=True, env=env, timeout=60)
    assert "Traceback" not in proc.stderr, proc.stderr
    assert proc.returncode == 1 and "FAILED (exit -1) cannot start" in proc.stdout, proc.stdout
    assert "Permission denied" in (tmp_path / "out" / "epsilon=0.1" / "stderr.txt").read_text()


def test_stopped_member_continues_from_its_checkpoint(tmp_path):
    """SIGUSR1 to study.py stops the running member after a checkpoint (marker `stopped`,
    exit status 1, no later member started); the next `run` continues it with --restart,
    its observables are those of an uninterrupted run bit for bit, and its wall time is
    the sum of the two attempts."""
    require_exe()
    import csv
    import signal
    import time
    from test_checkpoint import NOT_STATE
    env = {**os.environ, "CELLPHASE_EXE": EXE}
    text = ("scene: SCENE\noutput: out\n"
            "set: {numerics.end_time: 1.0, numerics.dt: 0.002, output.checkpoints.every: 10}\n"
            "sweep: {numerics.epsilon: [0.08, 0.1]}\n")
    path = write_study(tmp_path, text)
    run = [sys.executable, str(STUDY), "run", str(path)]
    member = tmp_path / "out" / "epsilon=0.08"
    study = subprocess.Popen(run, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=env)
    deadline = time.time() + 120
    while not any(p.name != "checkpoint-0.cpk" for p in member.glob("checkpoints/*.cpk")):
        assert study.poll() is None and time.time() < deadline, "no checkpoint came"
        time.sleep(0.2)
    study.send_signal(signal.SIGUSR1)
    out, err = study.communicate(timeout=120)
    assert study.returncode == 1, out + err
    assert "epsilon=0.08: stopped with a checkpoint" in out, out
    assert "epsilon=0.1: not started" in out, out
    assert (member / "stopped").is_file() and not (tmp_path / "out" / "epsilon=0.1").exists()
    with open(member / "observables.csv") as f:
        stopped_at = int(list(csv.DictReader(f))[-1]["step"])
    assert 0 < stopped_at < 500
    assert "stopped with a checkpoint" in (tmp_path / "out" / "report.md").read_text()

    proc = subprocess.run(run, capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "epsilon=0.08: finished" in proc.stdout and "epsilon=0.1: finished" in proc.stdout
    done = json.loads((member / "done").read_text())
    assert len(done["attempts"]) == 2 and done["wall"] == pytest.approx(sum(done["attempts"]))
    assert "--restart" in (member / "command.txt").read_text()

    # The same member in one go.
    path = write_study(tmp_path, text.replace("out\n", "whole\n").replace("[0.08, 0.1]", "[0.08]"))
    run[-1] = str(path)
    proc = subprocess.run(run, capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr

    def rows(d):
        with open(d / "observables.csv") as f:
            return list(csv.DictReader(f))
    # Bit for bit: the same text in every column but the wall times (nan stays nan).
    resumed, whole = rows(member), rows(tmp_path / "whole" / "epsilon=0.08")
    assert [r["step"] for r in resumed] == [r["step"] for r in whole]
    for a, b in zip(resumed, whole):
        assert {k: v for k, v in a.items() if k not in NOT_STATE} == \
               {k: v for k, v in b.items() if k not in NOT_STATE}, a["step"]
