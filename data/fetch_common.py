"""What data/fetch.py and data/sources.py share: the cache's paths, the
errors a scene can end in, logging and running a command.

Standard library only, but for tqdm (Debian python3-tqdm: the progress bar's
log lines).
"""

import hashlib
import json
import subprocess
import sys
from pathlib import Path

from tqdm import tqdm

REPO = Path(__file__).resolve().parent.parent
DATA = REPO / "data"
MANIFEST = DATA / "manifest.json"
CACHE = DATA / "cache"
SCENES = CACHE / "scenes"
DEBS = CACHE / "debs"
NPMS = CACHE / "npm"
DOWNLOADS = CACHE / "downloads"
EXTRACTED = CACHE / "extracted"
TMP = CACHE / "tmp"
INDEX = SCENES / "index.json"
PROFILES = ("test", "quick", "standard", "full")


class SceneError(Exception):
    """A scene could not be obtained; the message says why."""


class Skipped(Exception):
    """An optional scene was not obtained (e.g. no network); not a failure."""


def log(msg):
    tqdm.write(msg, file=sys.stderr)


def run(cmd, cwd=None, what=None):
    """Runs cmd; raises SceneError with its output's tail when it fails."""
    try:
        proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True)
    except FileNotFoundError as e:
        raise SceneError(f"{what or cmd[0]}: {e.filename} is not installed") from e
    if proc.returncode != 0:
        tail = "\n    ".join(proc.stdout.strip().splitlines()[-8:])
        raise SceneError(f"{what or ' '.join(cmd)} failed (exit {proc.returncode}):\n    {tail}")
    return proc.stdout


def load_manifest(path=MANIFEST):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def source_key(entry):
    """What the cached file depends on: a change in these refetches it."""
    keys = ("kind", "package", "path", "member", "npm_version", "convert", "url", "generator")
    parts = {k: entry.get(k) for k in keys}
    # The nodes a conversion leaves out, only where there are some (so the
    # keys of entries without any, made before this field counted, stand).
    if entry.get("skip_nodes"):
        parts["skip_nodes"] = entry["skip_nodes"]
    blob = json.dumps(parts, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def scene_file(entry):
    return SCENES / f"{entry['name']}.{entry['format']}"
