"""Writing a benchmark's result table: one row per dict, floats to 6 significant digits."""
import csv


def write_csv(path, columns, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: (f"{r[k]:.6g}" if isinstance(r[k], float) else r[k])
                             for k in columns})


NOTES = "## What it shows"


def hand_written_notes(report):
    """The hand-written discussion of a report, from its "## What it shows" heading to the
    end ("" if the report or the heading is missing): a rerun writes it back unchanged."""
    if not report.exists() or NOTES not in report.read_text():
        return ""
    text = report.read_text()
    return text[text.index(NOTES):]


def write_report(path, lines):
    """Write a report's generated lines, followed by its hand-written "## What it shows"
    section if the report already had one."""
    notes = hand_written_notes(path)
    if notes:
        lines = lines + [notes.rstrip("\n"), ""]
    path.write_text("\n".join(lines))
