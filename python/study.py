#!/usr/bin/python3
"""Run a study (a convergence ladder or a parameter sweep) of a cellphase scene and report it.

  study.py run STUDY.yaml [--jobs N] [--mpi N]   run the members not yet done, write the report
  study.py report STUDY.yaml                     rewrite the report from the existing results

Each member runs in OUTPUT/<member>/ (observables.csv, stdout.txt, stderr.txt). After a
successful run the runner writes OUTPUT/<member>/done with the measured wall time, peak
memory and settings; members with that marker and the same settings are skipped. The
report is OUTPUT/report.md with error_vs_walltime.png (ladder) or end_state.png (sweep).
Long members can be stopped and continued: `kill -USR1 <pid of study.py>` (or Ctrl-C) stops
the running members after their current step with a checkpoint (marker OUTPUT/<member>/stopped)
and starts no others; the next `study.py run` continues them from their checkpoints, and
their wall time is the sum of the attempts. While members run, a line per running member
every minute (--progress) gives its simulated time and an estimate of the time left.
See docs/studies.md.
Exit status: 0 all members finished, 1 some member failed, 2 bad study file or usage.
"""
import argparse
import datetime
import json
import os
import platform
import shutil
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cellphase_results import ResultsError, read_observables  # noqa: E402
from study_file import StudyError, format_value, load_study  # noqa: E402
from study_progress import ProgressWatch, member_end_time  # noqa: E402
from study_report import write_convergence_report, write_sweep_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DONE = "done"      # marker of a finished member: JSON with wall time and peak memory
FAILED = "failed"  # marker of a failed member: JSON with exit status and message
STOPPED = "stopped"  # marker of a member stopped with a checkpoint: JSON with its wall time
STOPPED_EXIT = 5     # cellphase's exit status after SIGINT/SIGTERM/SIGUSR1 and a checkpoint


class Running:
    """The members' processes, so that a stop request reaches every one of them."""
    lock = threading.Lock()
    processes = set()
    stop_requested = False

    @classmethod
    def stop(cls, signum, frame):
        with cls.lock:
            cls.stop_requested = True
            for proc in cls.processes:
                # mpirun forwards SIGUSR1 to its ranks; cellphase checkpoints and exits 5.
                proc.send_signal(signal.SIGUSR1)


def find_executable(given=None):
    exe = given or os.environ.get("CELLPHASE_EXE") or ROOT / "build" / "cellphase"
    if not Path(exe).is_file():
        raise StudyError(f"cellphase executable {exe} not found "
                         "(build it, or pass --exe or set CELLPHASE_EXE)")
    return str(exe)


def mpi_prefix(ranks, jobs=1):
    """mpirun with one BLAS thread per rank: the ranks already use the cores."""
    if ranks <= 1:
        return []
    root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    over = ["--oversubscribe"] if ranks * jobs > (os.cpu_count() or 1) else []
    return ["mpirun", *root, *over, "-x", "OPENBLAS_NUM_THREADS", "-n", str(ranks)]


def run_command(args, run_dir, env=None):
    """Run args with stdout/stderr in run_dir; return (exit status, wall s, peak MB).

    os.wait4 gives the resource usage of this child alone (ru_maxrss is the largest
    resident set of it and its descendants), so members running at once are measured apart.
    """
    with open(run_dir / "stdout.txt", "w") as out, open(run_dir / "stderr.txt", "w") as err:
        t0 = time.perf_counter()
        with Running.lock:
            proc = subprocess.Popen(args, stdout=out, stderr=err, env={**os.environ, **(env or {})},
                                    start_new_session=True)  # a stop comes from Running.stop
            Running.processes.add(proc)
        _, status, usage = os.wait4(proc.pid, 0)
        with Running.lock:
            Running.processes.discard(proc)
        wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    return proc.returncode, wall, usage.ru_maxrss / 1024


def first_line(path):
    try:
        lines = [ln.strip() for ln in Path(path).read_text(errors="replace").splitlines()]
    except OSError:
        return ""
    return next((ln for ln in lines if ln), "")


def member_settings(study, member):
    """The `--set KEY=VALUE` arguments of a member's run (its done marker records them)."""
    # Studies need the observables only: no field output unless the study sets it.
    overrides = {"output.every": 0, "output.progress": "false", **member.overrides,
                 "output.directory": str(study.output / member.name)}
    return [f"{key}={format_value(value)}" for key, value in overrides.items()]


def run_member(exe, study, member, ranks=1, jobs=1, watch=None):
    """Run one member unless it is done with the same settings; return a status line.
    `watch` (a ProgressWatch) reports its progress while it runs."""
    run_dir = study.output / member.name
    settings = member_settings(study, member)
    if (run_dir / DONE).is_file():
        # Results of other settings (the study's `set` was edited) are not reused.
        if json.loads((run_dir / DONE).read_text()).get("settings") == settings:
            return f"{member.name}: done before, skipped"
    if Running.stop_requested:
        return f"{member.name}: not started (the study was stopped)"
    args = [exe, "run", str(study.scene)] + [a for s in settings for a in ("--set", s)]
    earlier = stopped_attempts(run_dir, settings)
    if earlier:
        args += ["--restart", str(run_dir)]
        for marker in (STOPPED, FAILED):
            (run_dir / marker).unlink(missing_ok=True)
    else:
        shutil.rmtree(run_dir, ignore_errors=True)  # a partial, failed or outdated attempt
        run_dir.mkdir(parents=True)
    (run_dir / "command.txt").write_text(" ".join(mpi_prefix(ranks, jobs) + args) + "\n")
    if watch:
        watch.started(member.name, run_dir, member_end_time(study.scene, member.overrides))
    try:
        code, wall, peak = run_command(mpi_prefix(ranks, jobs) + args, run_dir,
                                       env={"OPENBLAS_NUM_THREADS": "1"} if ranks > 1 else None)
    except OSError as e:  # the executable vanished or is being rebuilt: this member fails
        (run_dir / "stderr.txt").write_text(f"cannot start {args[0]}: {e}\n")
        code, wall, peak = -1, 0.0, 0.0
    finally:
        if watch:
            watch.finished(member.name)
    attempts = (earlier or []) + [wall]
    record = {"exit": code, "wall": sum(attempts), "peak_mb": peak, "ranks": ranks,
              "settings": settings, "attempts": attempts}
    if code == STOPPED_EXIT:
        (run_dir / STOPPED).write_text(json.dumps(record) + "\n")
        return (f"{member.name}: stopped with a checkpoint after {sum(attempts):.1f} s; "
                "`study.py run` continues it")
    if code == 0:
        (run_dir / DONE).write_text(json.dumps(record) + "\n")
        return f"{member.name}: finished in {wall:.1f} s"
    record["message"] = first_line(run_dir / "stderr.txt")
    (run_dir / FAILED).write_text(json.dumps(record) + "\n")
    return f"{member.name}: FAILED (exit {code}) {record['message']}"


def stopped_attempts(run_dir, settings):
    """Wall times of the earlier attempts of a member stopped with a checkpoint under the
    same settings (None if it cannot be continued)."""
    for marker in (STOPPED, FAILED):
        path = run_dir / marker
        if not path.is_file():
            continue
        record = json.loads(path.read_text())
        stopped = record.get("exit") == STOPPED_EXIT and record.get("settings") == settings
        if stopped and any((run_dir / "checkpoints").glob("*.cpk")):
            return record.get("attempts", [record["wall"]])
    return None


def collect(study):
    """Result dicts of all members (see study_report) from their run directories."""
    results = []
    for m in study.members:
        run_dir = study.output / m.name
        r = {"name": m.name, "eps": m.eps, "params": m.params, "obs": None,
             "status": "not run", "wall": None, "peak_mb": None}
        for marker in (DONE, STOPPED, FAILED):
            if (run_dir / marker).is_file():
                record = json.loads((run_dir / marker).read_text())
                r["wall"], r["peak_mb"] = record.get("wall"), record.get("peak_mb")
                r["ranks"] = record.get("ranks", 1)
                if marker == DONE:
                    r["status"] = "ok"
                elif marker == STOPPED or record.get("exit") == STOPPED_EXIT:
                    r["status"] = "stopped with a checkpoint (study.py run continues it)"
                else:
                    r["status"] = f"failed (exit {record['exit']}): " \
                                  f"{record.get('message', '')}".replace("|", "/")
                break
        try:
            r["obs"] = read_observables(run_dir)
        except ResultsError:
            pass
        results.append(r)
    return results


def report(study):
    results = collect(study)
    study.output.mkdir(parents=True, exist_ok=True)  # a report of a study not yet run
    title = f"Study {study.path.name}: {study.kind} of {os.path.relpath(study.scene, ROOT)}"
    common = ", ".join(f"`{k}={format_value(v)}`" for k, v in study.common.items()) or "none"
    preamble = (f"Written by `python/study.py` on {datetime.date.today()} on {platform.node()} "
                f"({os.cpu_count()} cores). Settings of every member: {common}.")
    if study.kind == "ladder":
        rules = ", ".join(f"{k} {v:g}" for k, v in study.rules.items())
        preamble += f" Ladder rules: {rules}."
        write_convergence_report(study.output, title, results, study.observables, preamble)
    else:
        write_sweep_report(study.output, title, results, study.sweep_keys, study.end_state,
                           preamble)
    print(f"report: {study.output / 'report.md'}")
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0].split("\n")[0],
        epilog=__doc__.split("\n\n", 1)[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    run_p = sub.add_parser("run", help="run the members not yet done and write the report")
    run_p.add_argument("study", help="study file (YAML)")
    run_p.add_argument("--jobs", type=int, default=1, help="members run at once (default 1)")
    run_p.add_argument("--mpi", type=int, default=1, help="MPI ranks per member (default 1)")
    run_p.add_argument("--exe", help="cellphase executable (default: $CELLPHASE_EXE, "
                                     "else build/cellphase)")
    run_p.add_argument("--progress", type=float, default=60, metavar="SECONDS",
                       help="print each running member's simulated time and an estimate of "
                            "the time left every SECONDS (default 60; 0: never)")
    rep_p = sub.add_parser("report", help="rewrite the report from the existing results")
    rep_p.add_argument("study", help="study file (YAML)")
    a = parser.parse_args(argv)
    try:
        study = load_study(a.study)
        if a.command == "run":
            if a.jobs < 1 or a.mpi < 1:
                raise StudyError("--jobs and --mpi must be at least 1")
            if a.progress < 0:
                raise StudyError(f"--progress {a.progress:g}: seconds between progress lines, "
                                 "0 or more (0: none)")
            exe = find_executable(a.exe)
            study.output.mkdir(parents=True, exist_ok=True)
            print(f"{len(study.members)} members in {study.output}", flush=True)
            for signum in (signal.SIGUSR1, signal.SIGINT, signal.SIGTERM):
                signal.signal(signum, Running.stop)
            watch = ProgressWatch(a.progress)
            with ThreadPoolExecutor(max_workers=a.jobs) as pool:
                futures = [pool.submit(run_member, exe, study, m, a.mpi, a.jobs, watch)
                           for m in study.members]
                for f in futures:
                    print(f.result(), flush=True)
            watch.stop.set()
        results = report(study)
    except StudyError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except ValueError as e:  # e.g. an observable the runs do not write
        print(f"error: {study.path}: {e}", file=sys.stderr)
        return 2
    return 0 if all(r["status"] == "ok" for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
