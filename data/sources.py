"""Where scenes come from, one function per manifest `kind` (data/fetch.py's
docstring lists them): Debian packages and the archives inside them, npm
tarballs, Blender, the generators and URLs. Each writes the scene's file to
`dest` and adds what it downloaded to `stats`; failures raise SceneError.
"""

import gzip
import json
import os
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile
import urllib.error
import urllib.request
import zipfile
from pathlib import Path

from tqdm import tqdm

import parts
from fetch_common import (CACHE, DEBS, DOWNLOADS, EXTRACTED, NPMS, REPO, SCENES, TMP,
                          SceneError, Skipped, log, run)

# Blender's own monkey as the report used it (//cc/seed:row18_test meets it):
# quads, triangulated by the loader (assimp) into 968 triangles.
SUZANNE_EXPR = (
    "import bpy; bpy.ops.object.select_all(action='SELECT'); bpy.ops.object.delete(); "
    "bpy.ops.mesh.primitive_monkey_add(size=2, location=(0,0,0)); "
    "bpy.ops.wm.obj_export(filepath={path!r})"
)

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
            parts.prepare_parts(entry, sys.modules[__name__], tools, stats, cache_paths,
                                CACHE / parts.PARTS_DIR_NAME)))
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
