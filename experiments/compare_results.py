#!/usr/bin/python3
"""Compares two kd-tree result files (e.g. a local and a SLURM run of the same
matrix): every non-timing statistic must be equal for every (scene, variant).

    /usr/bin/python3 experiments/compare_results.py A/kdtree.jsonl B/kdtree.jsonl

Timings (T_B, T_R, perf, seconds, rays per second, runs, wall time, the
paired ratios to Embree) and
provenance (node, commit, CPU, job ids, how many jobs ran at once) are only
reported, never compared.
Exit 0 when every pair agrees and both files hold the same set of successful
(scene, variant) pairs; 1 otherwise, listing the differences.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import jsonl  # noqa: E402  (experiments/jsonl.py: the results files' one reader)

# Keys whose values legitimately differ between two runs.
TIMING_WORDS = ("T_B", "T_R", "perf", "seconds", "_s", "per_s", "runs",
                "wall", "time", "date", "paired_ratio")
PROVENANCE = {"node", "backend", "commit", "git_commit", "cpu", "job", "host",
              "command", "error", "out", "png", "image", "dump", "build_flags",
              "mesh", "hostname", "threads_available", "load",
              "concurrent_jobs", "provenance", "timing"}


def is_timing(key):
    return any(w in key for w in TIMING_WORDS)


def flatten(rec, prefix=""):
    out = {}
    for key, value in rec.items():
        name = prefix + key
        if key in PROVENANCE or is_timing(key):
            continue
        if isinstance(value, dict):
            out.update(flatten(value, name + "."))
        elif isinstance(value, list):
            continue  # per-run arrays are timings
        else:
            out[name] = value
    return out


def latest_ok(path):
    """The last successful record of each (scene, variant) in path; a line
    that is not a record raises ValueError naming file and line (jsonl.read),
    and a missing file is OSError."""
    if not os.path.exists(path):
        raise FileNotFoundError("no file %s" % path)
    return {(rec["scene"], rec["preset"]): rec for rec in jsonl.read(path) if rec.get("ok")}


def compare(a_path, b_path):
    """[difference strings] (empty when the files agree)."""
    a, b = latest_ok(a_path), latest_ok(b_path)
    diffs = []
    for key in sorted(set(a) | set(b)):
        if key not in a or key not in b:
            diffs.append("%s/%s only in %s" % (key[0], key[1],
                                                a_path if key in a else b_path))
            continue
        fa, fb = flatten(a[key]), flatten(b[key])
        for name in sorted(set(fa) | set(fb)):
            if fa.get(name) != fb.get(name):
                diffs.append("%s/%s %s: %r != %r" % (key[0], key[1], name,
                                                      fa.get(name), fb.get(name)))
    return diffs, len(set(a) & set(b))


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        diffs, common = compare(argv[1], argv[2])
    except (OSError, ValueError) as e:
        print("compare: %s" % e, file=sys.stderr)
        return 2
    for d in diffs[:50]:
        print("compare: " + d)
    print("compare: %d (scene, variant) pairs, %d differences"
          % (common, len(diffs)))
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
