#!/usr/bin/python3
"""Fails when a tracked file names a path outside the repository.

    /usr/bin/python3 experiments/self_contained.py [ROOT]

A clone holds only the repository: a pointer to the machine's shared notes
beside the checkout, to the workspace directory or to a home directory (the
patterns of OUTSIDE) would send a reader to files they do not have. Neither
this file nor its test spells such a path out, so they are scanned like any
other. Every
file `git ls-files` lists is scanned (binary files skipped); each hit is
printed as FILE:LINE: TEXT, exit code 1 when any. experiments/test.sh (the
README's test command) runs it before bazel test. Standard library only.
"""

import os
import re
import subprocess
import sys

OUTSIDE = re.compile(r"\.\.[/]shared\b|(?<![\w.~-])[/](?:work|root|home)[/]|\bshared[/](?:notes|seed)[/]")


def outside_references(root, files):
    """[(file, line number, line)] of the files (relative to root) whose
    text names a path outside the repository."""
    hits = []
    for name in files:
        path = os.path.join(root, name)
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError:
            continue  # listed but absent (a deleted, uncommitted file)
        if b"\0" in data:
            continue  # binary
        text = data.decode("utf-8", errors="replace")
        for number, line in enumerate(text.splitlines(), 1):
            if OUTSIDE.search(line):
                hits.append((name, number, line.strip()))
    return hits


# Generated or fetched, never tracked: skipped when walking a copy without git.
UNTRACKED = ("out", "data/cache", "report/build", "report/generated", ".git")


def tracked_files(root):
    """`git ls-files` of root; for a copy that is not a git checkout, every
    file but the generated ones (UNTRACKED, bazel-*)."""
    try:
        listed = subprocess.run(["git", "-C", root, "ls-files", "-z"], stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, check=True).stdout.decode()
        return [f for f in listed.split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(root):
            rel = os.path.relpath(d, root)
            dirs[:] = [x for x in dirs if not x.startswith("bazel-")
                       and os.path.normpath(os.path.join(rel, x)) not in UNTRACKED]
            files += [os.path.normpath(os.path.join(rel, n)) for n in names]
        return files


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    root = argv[0] if argv else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    files = tracked_files(root)
    hits = outside_references(root, files)
    for name, number, line in hits:
        print("%s:%d: names a path outside the repository: %s" % (name, number, line[:200]))
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main())
