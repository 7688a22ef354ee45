"""Readers for the pipeline's inputs: the scene manifest, what the raw result
files written by experiments/*.py hold (the files themselves are read by
experiments/jsonl.py, which refuses a line that is not a record), and the
report's own (seed) numbers.

Readers are tolerant about shape (the manifest may be a list or a dict with
"scenes") and strict about content (a malformed entry is an error, not a
silently dropped record).
"""

import json
import os

import pandas as pd

SEED_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seed")


def load_manifest(path):
    """Returns the manifest's scenes as a list of dicts, in manifest order,
    each with an added "number": the 1-based position in the manifest (or the
    scene's own "number" if the manifest gives one). The number is stable
    whatever subset a profile or a fetch obtains, so tables can cite it."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if isinstance(data, dict):
        if "scenes" not in data:
            raise ValueError("%s: a dict manifest needs a 'scenes' key" % path)
        data = data["scenes"]
    if not isinstance(data, list):
        raise ValueError("%s: manifest scenes must be a list" % path)
    scenes, seen = [], set()
    for i, scene in enumerate(data):
        if not isinstance(scene, dict) or not scene.get("name"):
            raise ValueError("%s: scene %d has no name" % (path, i))
        if scene["name"] in seen:
            raise ValueError("%s: duplicate scene %r" % (path, scene["name"]))
        seen.add(scene["name"])
        scene = dict(scene)
        scene.setdefault("number", i + 1)
        scenes.append(scene)
    return scenes


def latest_scene_records(records):
    """One record per scene: the last successful one if any, else the last
    failure. (Raw files are append-only, so a re-run appends; the newest
    successful measurement wins.)"""
    best = {}
    for rec in records:
        name = rec.get("scene")
        if not name:
            continue
        prev = best.get(name)
        if prev is None or rec.get("ok") or not prev.get("ok"):
            best[name] = rec
    return best


def load_machine(results_dir):
    """machine.json as a dict ({} when absent)."""
    path = os.path.join(results_dir, "machine.json")
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def load_seed_table1(path=None):
    """The report's Table 1 (18 rows) as a DataFrame indexed by report_scene."""
    path = path or os.path.join(SEED_DIR, "table1.csv")
    df = pd.read_csv(path, dtype={"name": str})
    return df.set_index("report_scene", drop=False)


def load_seed_tables2_10(path=None):
    """The report's Tables 2-10 in long format (analysis/seed/tables2_10.csv):
    one row per printed cell with table, report_scene, variant (our preset
    name), metric, value (float; NaN where the seed prints "-"), printed (the
    cell's text as printed) and seed_line. See analysis/seed/README.md."""
    path = path or os.path.join(SEED_DIR, "tables2_10.csv")
    df = pd.read_csv(path, dtype={"variant": str, "metric": str,
                                  "printed": str})
    df["value"] = pd.to_numeric(df["value"], errors="raise")
    return df
