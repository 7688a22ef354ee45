"""The README's table of end-to-end times, from reproduce.sh logs.

    /usr/bin/python3 experiments/step_times.py LABEL=LOG [LABEL=LOG ...]

reproduce.sh prints `==> [HH:MM:SS, +N s] step` before each step and
`reproduce: report at ... (N s in all)` at the end; a step's time is the
difference between its line and the next. Prints a Markdown table: one row
per step (in the order of the first log; a step a log lacks is a dash), one
column per log, and the total. Several steps may be merged into one row by
ROWS below (the README's grouping); an unknown step gets a row of its own.
"""

import re
import sys

STEP = re.compile(r"^==> \[[0-9:]+, \+(\d+) s\] (.*)$")
TOTAL = re.compile(r"^reproduce: report at .* \((\d+) s in all\)$")

# (row, prefix of the steps it sums), in the table's order.
ROWS = [
    ("set-up, fetch", ("set-up", "fetch scenes")),
    ("build tools", ("build tools",)),
    ("load scenes, scene 18", ("load scenes", "scene 18")),
    ("kd-tree matrix", ("kd-tree matrix",)),
    ("in-plane triangles", ("in-plane triangles",)),
    ("robustness (build, suite, cost)", ("robustness",)),
    ("accuracy versus time", ("accuracy versus time",)),
    ("analysis and LaTeX", ("analysis", "report (LaTeX)")),
]


def step_seconds(lines):
    """([(step, seconds)] in order, total seconds or None) of a log; the last
    step ends at the total (or is dropped without one: it did not finish)."""
    marks, total = [], None
    for line in lines:
        line = line.rstrip("\n")
        m = STEP.match(line)
        if m:
            marks.append((m.group(2), int(m.group(1))))
            continue
        m = TOTAL.match(line)
        if m:
            total = int(m.group(1))
    out = []
    for i, (name, start) in enumerate(marks):
        end = marks[i + 1][1] if i + 1 < len(marks) else total
        if end is not None:
            out.append((name, end - start))
    return out, total


def row_of(step):
    for row, prefixes in ROWS:
        if any(step.startswith(p) for p in prefixes):
            return row
    return step


def fmt(seconds):
    if seconds is None:
        return "-"
    m, s = divmod(int(seconds), 60)
    return "%d min %d s" % (m, s) if m else "%d s" % s


def table(columns):
    """Markdown for [(label, [(step, seconds)], total)]."""
    rows = [r for r, _ in ROWS]
    sums = []
    for _, steps, _ in columns:
        by_row = {}
        for name, sec in steps:
            row = row_of(name)
            by_row[row] = by_row.get(row, 0) + sec
            if row not in rows:
                rows.append(row)
        sums.append(by_row)
    lines = ["| step | " + " | ".join(label for label, _, _ in columns) + " |",
             "|---|" + "---:|" * len(columns)]
    for row in rows:
        if any(row in s for s in sums):
            lines.append("| %s | %s |" % (row, " | ".join(fmt(s.get(row)) for s in sums)))
    lines.append("| **in all** | %s |" % " | ".join(
        "**%s**" % fmt(total) if total is not None else "(not finished)"
        for _, _, total in columns))
    return "\n".join(lines)


def main(argv):
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    columns = []
    for arg in argv:
        label, sep, path = arg.partition("=")
        if not sep:
            print("step_times: expected LABEL=LOG, got %r" % arg, file=sys.stderr)
            return 2
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                steps, total = step_seconds(f)
        except OSError as e:
            print("step_times: %s: %s" % (path, e.strerror), file=sys.stderr)
            return 1
        columns.append((label, steps, total))
    print(table(columns))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
