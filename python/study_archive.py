"""Keep the results of a study's finished members beside the benchmark reports.

A long member (an hour or more) lives in the study's output directory, which a new machine
or a clean checkout does not have. `archive_members` copies each finished member's
observables (the study's observables and end-state quantities, time, step, dofs and the
wall_* cost columns, as written by cellphase) and its done marker to ARCHIVE/<member>.csv
and ARCHIVE/<member>.json;
`restore_members` puts them back into run directories that have no finished result, when
they were made with the member's present settings (the output directory aside), so that
`study.py run` skips those members and the report reads them as if they had just run.
"""
import csv
import json
from pathlib import Path

from study import DONE, FAILED, STOPPED, member_settings

KEPT = ["time", "step", "dofs"]  # besides the study's observables and the wall_* columns


def _portable(settings):
    """The settings without the output directory, which depends on the checkout's path."""
    return [s for s in settings if not s.startswith("output.directory=")]


def archive_members(study, archive):
    """Copy every finished member to ARCHIVE; return the names copied."""
    archive = Path(archive)
    copied = []
    for m in study.members:
        run_dir = study.output / m.name
        if not (run_dir / DONE).is_file() or not (run_dir / "observables.csv").is_file():
            continue
        with open(run_dir / "observables.csv", newline="") as f:
            rows = list(csv.reader(f))
        header = rows[0]
        wanted = set(KEPT) | set(study.observables) | set(study.end_state)
        keep = [i for i, name in enumerate(header) if name in wanted or name.startswith("wall_")]
        archive.mkdir(parents=True, exist_ok=True)
        with open(archive / f"{m.name}.csv", "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            # Whole rows only: the values are cellphase's own text, not reformatted.
            w.writerows([[r[i] for i in keep] for r in rows if len(r) == len(header)])
        record = json.loads((run_dir / DONE).read_text())
        record["settings"] = _portable(record.get("settings", []))
        # A restored member archived again is its archive: not the path it came from.
        record.pop("restored_from", None)
        (archive / f"{m.name}.json").write_text(json.dumps(record, indent=1) + "\n")
        copied.append(m.name)
    return copied


def restore_members(study, archive):
    """Put archived members back where their run directory has no finished result; return
    (restored names, [(name, reason)] for archived members not restored)."""
    archive = Path(archive)
    restored, skipped = [], []
    for m in study.members:
        source = archive / f"{m.name}.json"
        run_dir = study.output / m.name
        if not source.is_file() or (run_dir / DONE).is_file():
            continue
        record = json.loads(source.read_text())
        settings = member_settings(study, m)
        if record.get("settings") != _portable(settings):
            skipped.append((m.name, "archived with other settings (the study was edited)"))
            continue
        run_dir.mkdir(parents=True, exist_ok=True)
        for marker in (FAILED, STOPPED):  # of an attempt the archived run supersedes
            (run_dir / marker).unlink(missing_ok=True)
        (run_dir / "observables.csv").write_text((archive / f"{m.name}.csv").read_text())
        record.update(settings=settings, restored_from=str(source))
        (run_dir / DONE).write_text(json.dumps(record) + "\n")
        restored.append(m.name)
    return restored, skipped
