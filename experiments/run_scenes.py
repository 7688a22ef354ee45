#!/usr/bin/python3
"""Loads every obtained scene of a profile with scene_info; records the raw
results and the machine they were measured on.

    /usr/bin/python3 experiments/run_scenes.py --profile quick [--out out]

Reads   data/manifest.json (which scenes belong to the profile) and
        data/cache/scenes/index.json (which of them data/fetch.py obtained),
runs    bazel-out/k8-opt/bin/cc/tools/scene_info --mesh PATH --name NAME
            --cache_dir data/cache/soups
        for each scene (a failing scene is recorded, not fatal),
appends one JSON line per scene to OUT/results/scenes.jsonl (append-only:
        raw results are never edited),
writes  OUT/results/machine.json (the machine of the latest run) and appends
        the same record to OUT/results/machines.jsonl (every run's machine).

Resumable: a scene already recorded successfully with the same mesh path and
file size is skipped (use --force to measure again; the newest successful
record wins in the analysis). Failed scenes are tried again on every run.

Exit status: 0 when every scene was attempted (even if some failed), 2 when
nothing could be attempted (no index, no scene_info binary).
Standard library only (tqdm is used for the progress bar when present).
"""

import argparse
import datetime
import hashlib
import json
import os
import platform
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))
import jsonl  # noqa: E402  (the results files' one reader and appender)
import provenance  # noqa: E402  (the machine's fields, as the C++ records')

DEFAULT_MANIFEST = os.path.join(ROOT, "data", "manifest.json")
DEFAULT_INDEX = os.path.join(ROOT, "data", "cache", "scenes", "index.json")
DEFAULT_SCENE_INFO = provenance.opt_binary("cc", "tools", "scene_info")
DEFAULT_SOUP_CACHE = os.path.join(ROOT, "data", "cache", "soups")

SCENES_FILE = "scenes.jsonl"

try:
    from tqdm import tqdm as _tqdm
except ImportError:  # the progress bar is a nicety, not a dependency
    _tqdm = None


class SetupError(Exception):
    """Nothing can be measured (missing index or binary)."""


# --------------------------------------------------------------------------
# Inputs


def load_manifest(path):
    """Manifest scenes as a list of dicts ([] if the file is absent).
    Accepts a list or a dict with "scenes"."""
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if isinstance(data, dict):
        data = data.get("scenes", [])
    return [s for s in data if isinstance(s, dict) and s.get("name")]


def load_index(path):
    """{name: absolute mesh path} from fetch.py's index. Accepts
    {"name": "path"}, {"name": {"file" or "path": ...}} (data/fetch.py writes
    "file"), or [{"name":, "path":}], also
    wrapped as {"scenes": ...}. Relative paths are resolved against the repo
    root, then against the index's directory."""
    if not os.path.exists(path):
        raise SetupError("no scene index at %s: run data/fetch.py first"
                         % path)
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if isinstance(data, dict) and isinstance(data.get("scenes"), (list, dict)):
        data = data["scenes"]
    entries = []
    if isinstance(data, dict):
        for name, value in data.items():
            if isinstance(value, dict):
                value = value.get("file") or value.get("path")
            entries.append((name, value))
    elif isinstance(data, list):
        for item in data:
            if isinstance(item, dict):
                entries.append((item.get("name"), item.get("file") or item.get("path")))
    else:
        raise SetupError("%s: unrecognised index shape" % path)
    index_dir = os.path.dirname(os.path.abspath(path))
    out = {}
    for name, mesh in entries:
        if not name or not mesh:
            continue
        out[name] = resolve_mesh(mesh, index_dir)
    return out


def resolve_mesh(mesh, index_dir):
    if os.path.isabs(mesh):
        return mesh
    for base in (ROOT, index_dir):
        candidate = os.path.normpath(os.path.join(base, mesh))
        if os.path.exists(candidate):
            return candidate
    return os.path.normpath(os.path.join(ROOT, mesh))


def select_scenes(manifest, index, profile):
    """[(name, mesh path)] of the profile's obtained scenes, manifest order.

    A manifest scene belongs to the profile when its "profiles" list names it
    (a scene without "profiles" belongs to every profile). Without a manifest,
    every indexed scene is taken. Indexed scenes the manifest does not know
    are reported and skipped."""
    if not manifest:
        return sorted(index.items())
    chosen = []
    known = set()
    for scene in manifest:
        name = scene["name"]
        known.add(name)
        profiles = scene.get("profiles")
        if profiles is not None and profile not in profiles:
            continue
        if name in index:
            chosen.append((name, index[name]))
    unknown = sorted(set(index) - known)
    if unknown:
        print("scenes: ignoring indexed scenes not in the manifest: %s"
              % ", ".join(unknown), file=sys.stderr)
    return chosen


# --------------------------------------------------------------------------
# Machine


def _run(cmd, cwd=ROOT):
    try:
        out = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True,
                             timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return out.stdout if out.returncode == 0 else None


def memory_gib(meminfo="/proc/meminfo"):
    try:
        with open(meminfo, encoding="utf-8") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    return round(int(line.split()[1]) / 1024.0 / 1024.0, 1)
    except (OSError, ValueError, IndexError):
        pass
    return None


def os_name():
    pretty = None
    try:
        with open("/etc/os-release", encoding="utf-8") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    pretty = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return "%s, Linux %s" % (pretty or platform.system(), platform.release())


def sha256_of(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def machine_info(scene_info=None):
    compiler = _run(["g++", "--version"])
    # The code as every record names it (cc/base/source_id.sh): untracked
    # files count as changes, and a pinned identity (KDTREE_SOURCE_ID) is
    # honoured.
    code = provenance.code_identity(ROOT)
    # The CPU as the C++ records name it; the model name falls back to
    # Python's name for the platform where /proc/cpuinfo has none (ARM).
    cpu = provenance.machine()
    info = {
        "recorded_at": datetime.datetime.now(datetime.timezone.utc)
        .isoformat(timespec="seconds"),
        "cpu_model": cpu["cpu_model"] or platform.processor() or platform.machine() or None,
        "cpu_id": cpu["cpu_id"],
        "cpu_caches": cpu["cpu_caches"],
        "cpu_count": os.cpu_count(),
        "memory_gib": memory_gib(),
        "os": os_name(),
        "compiler": compiler.splitlines()[0].strip() if compiler else None,
        "python": platform.python_version(),
        "git_commit": code["commit"],
        "git_dirty": code["dirty"] if code["source_tree"] else None,
        "source_tree": code["source_tree"],
    }
    if scene_info and os.path.exists(scene_info):
        rel = os.path.relpath(scene_info, ROOT)
        info["scene_info"] = scene_info if rel.startswith("..") else rel
        info["scene_info_sha256"] = sha256_of(scene_info)
    return info


# --------------------------------------------------------------------------
# Running scene_info


def last_json_line(text):
    for line in reversed(text.splitlines()):
        line = line.strip()
        if line.startswith("{"):
            try:
                value = json.loads(line)
            except json.JSONDecodeError:
                continue
            if isinstance(value, dict):
                return value
    return None


def measure(name, mesh, scene_info, soup_cache, timeout):
    """Runs scene_info on one scene; returns the raw record (never raises
    for a scene-level failure)."""
    record = {
        "scene": name,
        "mesh": mesh,
        "mesh_bytes": os.path.getsize(mesh) if os.path.exists(mesh) else None,
        "started_at": datetime.datetime.now(datetime.timezone.utc)
        .isoformat(timespec="seconds"),
    }
    cmd = [scene_info, "--mesh", mesh, "--name", name,
           "--cache_dir", soup_cache]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True,
                              timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        record.update(ok=False, returncode=None,
                      error="timed out after %ss" % timeout,
                      wall_s=round(time.monotonic() - t0, 3))
        return record
    except OSError as e:
        record.update(ok=False, returncode=None, error=str(e),
                      wall_s=round(time.monotonic() - t0, 3))
        return record
    record["wall_s"] = round(time.monotonic() - t0, 3)
    record["returncode"] = proc.returncode
    result = last_json_line(proc.stdout) if proc.returncode == 0 else None
    if proc.returncode != 0 or result is None:
        err = proc.stderr.strip() or proc.stdout.strip()
        if proc.returncode == 0:
            err = "no JSON line on stdout: " + err
        record.update(ok=False, error=err[-2000:] or "exit %d"
                      % proc.returncode)
        return record
    # scene_info's own fields, then ours on top ("scene"/"mesh" agree).
    merged = dict(result)
    merged.update(record)
    merged["ok"] = True
    if proc.stderr.strip():
        merged["stderr"] = proc.stderr.strip()[-2000:]
    return merged


def run(profile, out_dir, manifest=DEFAULT_MANIFEST, index=DEFAULT_INDEX,
        scene_info=DEFAULT_SCENE_INFO, soup_cache=DEFAULT_SOUP_CACHE,
        timeout=3600.0, force=False, progress=True):
    """Measures the profile's obtained scenes. Returns (done, skipped,
    failed) counts. Raises SetupError when nothing can be measured."""
    scene_info = os.path.abspath(scene_info)
    if not os.access(scene_info, os.X_OK):
        raise SetupError("no scene_info binary at %s: run "
                         "'bazel build -c opt //cc/tools:scene_info'"
                         % scene_info)
    chosen = select_scenes(load_manifest(manifest), load_index(index),
                           profile)
    results = os.path.join(out_dir, "results")
    os.makedirs(results, exist_ok=True)
    os.makedirs(soup_cache, exist_ok=True)

    machine = machine_info(scene_info)
    machine["profile"] = profile
    with open(os.path.join(results, "machine.json.tmp"), "w",
              encoding="utf-8") as f:
        json.dump(machine, f, indent=2, sort_keys=True)
        f.write("\n")
    os.replace(os.path.join(results, "machine.json.tmp"),
               os.path.join(results, "machine.json"))
    jsonl.append(os.path.join(results, "machines.jsonl"), machine)

    path = os.path.join(results, SCENES_FILE)
    done_before = {(r.get("scene"), r.get("mesh"), r.get("mesh_bytes"))
                   for r in jsonl.read_resuming(path, "resume") if r.get("ok")}
    todo, skipped = [], 0
    for name, mesh in chosen:
        size = os.path.getsize(mesh) if os.path.exists(mesh) else None
        if not force and (name, mesh, size) in done_before:
            skipped += 1
        else:
            todo.append((name, mesh))
    if skipped:
        print("scenes: %d scene(s) already recorded, skipped" % skipped)

    bar = _tqdm(todo, desc="scene_info", unit="scene") \
        if (_tqdm and progress) else None
    say = bar.write if bar is not None else print
    failed = 0
    for name, mesh in (bar if bar is not None else todo):
        if bar is not None:
            bar.set_postfix_str(name)
        record = measure(name, mesh, scene_info, soup_cache, timeout)
        record["profile"] = profile
        record["git_commit"] = machine.get("git_commit")
        jsonl.append(path, record)
        if record["ok"]:
            say("  %-24s %12s triangles  %.2fs%s" % (
                name, format(record.get("n_tri", 0), ","), record["wall_s"],
                "  (soup cache)" if record.get("from_cache") else ""))
        else:
            failed += 1
            lines = record["error"].splitlines() or ["?"]
            say("  %-24s FAILED: %s" % (name, lines[-1]))
    if bar is not None:
        bar.close()
    print("scenes: profile %s: %d measured (%d failed), %d skipped; -> %s"
          % (profile, len(todo), failed, skipped, path))
    return len(todo), skipped, failed


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Load every obtained scene of a profile with scene_info.")
    parser.add_argument("--profile", default="quick",
                        help="test, quick, standard or full (default quick)")
    parser.add_argument("--out", default=os.path.join(ROOT, "out"),
                        help="output root; results go to OUT/results")
    parser.add_argument("--manifest", default=DEFAULT_MANIFEST)
    parser.add_argument("--index", default=DEFAULT_INDEX)
    parser.add_argument("--scene_info", default=DEFAULT_SCENE_INFO)
    parser.add_argument("--cache_dir", default=DEFAULT_SOUP_CACHE,
                        help="triangle-soup cache passed to scene_info")
    parser.add_argument("--timeout", type=float, default=3600.0,
                        help="seconds per scene (default 3600)")
    parser.add_argument("--force", action="store_true",
                        help="measure again scenes already recorded")
    parser.add_argument("--no_progress", action="store_true")
    args = parser.parse_args(argv)
    try:
        run(args.profile, args.out, manifest=args.manifest, index=args.index,
            scene_info=args.scene_info, soup_cache=args.cache_dir,
            timeout=args.timeout, force=args.force,
            progress=not args.no_progress)
    except SetupError as e:
        print("scenes: error: %s" % e, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
