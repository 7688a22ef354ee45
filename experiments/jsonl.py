"""The results files' one format: JSON lines, one record (a JSON object) a
line, appended to and never edited. One reader and one appender for every
program that reads or writes them: the runners (run_scenes, run_matrix,
run_accuracy, run_planar, the SLURM backend matrix_slurm and cc/robust's
suite), the benches' drivers and summaries (bench.py, pair_variants.py,
pair_binaries.py, tree_fingerprints.py), the SLURM check
(compare_results.py) and the analysis (analysis/context.py). Standard
library only, so the runners and the SLURM check need neither pandas nor
the analysis."""

import json
import os
import sys

# What a line that does not parse most likely is, and what to do about it.
CUT_SHORT_HINT = ("a record cut short by an interrupted run? Delete that line; a runner "
                  "resuming passes over it and runs its job again")


def read(path, on_bad=None):
    """The records of a JSON-lines file, in order: [] when the file does not
    exist, blank lines skipped. A line that is not a JSON object raises
    ValueError naming the file and the line (with CUT_SHORT_HINT when it
    does not parse: JSON cut short, or bytes that are not UTF-8); given
    on_bad, on_bad(path, lineno) is called instead and the line passed over
    (read_resuming)."""
    records = []
    if not os.path.exists(path):
        return records
    with open(path, "rb") as f:
        for lineno, raw in enumerate(f, 1):
            try:
                line = raw.decode("utf-8").strip()
                if not line:
                    continue
                record = json.loads(line)
                why = None if isinstance(record, dict) else (
                    "a JSON %s, not a record" % type(record).__name__)
            except ValueError as e:  # UnicodeDecodeError, JSONDecodeError
                record, why = None, "%s (%s)" % (e, CUT_SHORT_HINT)
            if why is not None:
                if on_bad is None:
                    raise ValueError("%s:%d: %s" % (path, lineno, why))
                on_bad(path, lineno)
                continue
            records.append(record)
    return records


def read_resuming(path, who):
    """read() for a run that resumes from path: a line that is not a JSON
    record (a run killed or out of disk while appending leaves one cut
    short) is passed over with a warning, `who` first, naming the file and
    line, so its job runs again. The analysis reads the same files strictly."""
    def warn(path, lineno):
        print("%s: %s:%d is not a JSON record (cut short by an interrupted "
              "run?): passed over, its job runs again; analysis/make_all.py "
              "refuses the file until that line is deleted" % (who, path, lineno),
              file=sys.stderr)
    return read(path, on_bad=warn)


def ends_cut_short(path):
    """Whether the file's last line lacks its newline (a record cut short by
    a run killed or out of disk while appending)."""
    try:
        with open(path, "rb") as f:
            if f.seek(0, os.SEEK_END) == 0:
                return False
            f.seek(-1, os.SEEK_END)
            return f.read(1) != b"\n"
    except FileNotFoundError:
        return False


def append(path, record):
    """One line, keys sorted, flushed and synced: an interrupted run keeps
    what it did. After a line cut short, the record starts a line of its own
    (the cut one is left as it is: raw results are never edited)."""
    line = json.dumps(record, sort_keys=True) + "\n"
    if ends_cut_short(path):
        line = "\n" + line
    with open(path, "a", encoding="utf-8") as f:
        f.write(line)
        f.flush()
        os.fsync(f.fileno())
