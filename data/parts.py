"""Conversions and generator parts for data/fetch.py.

Conversions (manifest `convert`), each run as a child process so that a crash
in a reader cannot take the fetcher down:
  q3-bsp      `member` is a Quake 3 map (maps/NAME.bsp) inside the package's
              .pk3; //cc/scenes:q3_bsp_tool (our reader, cc/scenes/q3_bsp.h)
              writes its drawn surfaces as PLY. assimp 5.2's Q3BSP reader
              returns degenerate triangles for these maps.
  assimp-ply  the file (or `member`) goes through assimp in
              //cc/scenes:mesh_info --ply_out: flattened, triangulated, as PLY
              (e.g. the TORCS .acc variant of AC3D, which only assimp reads);
              the entry's `skip_nodes` names nodes to leave out.

Generator parts (`generator.parts`, for the plant and courtyard generators):
a list of {"role", "height", and either "scene" (another manifest scene) or
"package" + "path" [+ "member" of a .zip/.sh3f archive in it] [+ "up_axis"]}.
Each part becomes data/cache/parts/KEY.ply (KEY: a hash of the part's
source), converted once through mesh_info --ply_out, and is passed to
//cc/scenes:generate as --parts=role:height:path[:up_axis].
"""

import hashlib
import json
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

PARTS_DIR_NAME = "parts"


def part_key(part):
    blob = json.dumps({k: part.get(k) for k in ("scene", "package", "path", "member")},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def run_child(cmd, what, error):
    """Runs a converter; raises `error` (fetch.SceneError) on failure or crash."""
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        why = (f"crashed (signal {-proc.returncode})" if proc.returncode < 0
               else (proc.stderr.strip() or proc.stdout.strip())[-600:])
        raise error(f"{what} failed: {why}")
    lines = proc.stdout.strip().splitlines()
    return json.loads(lines[-1]) if lines and lines[-1].startswith("{") else {}


def assimp_to_ply(tools, src, dest, error, skip_nodes=None):
    """Any file assimp reads -> flattened binary PLY (mesh_info --ply_out); nodes
    named in `skip_nodes` (helper geometry) are left out with their subtrees."""
    cmd = [str(tools.ensure() / "mesh_info"), str(src), f"--ply_out={dest}"]
    if skip_nodes:
        cmd.append("--skip_nodes=" + ",".join(skip_nodes))
    return run_child(cmd, f"mesh_info --ply_out {Path(src).name}", error)


def q3_bsp_to_ply(tools, bsp, dest, error):
    return run_child([str(tools.ensure() / "q3_bsp_tool"), f"--bsp={bsp}", f"--out={dest}"],
                     f"q3_bsp_tool {Path(bsp).name}", error)


def extract_many_from_deb(deb, paths, dest_dir, error):
    """Copies each ./path of `paths` out of the .deb into dest_dir/path, in one
    pass over the package (FlightGear's is 1.3 GB)."""
    wanted = {p.lstrip("./") for p in paths}
    proc = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", str(deb)], stdout=subprocess.PIPE)
    try:
        with tarfile.open(fileobj=proc.stdout, mode="r|") as tar:
            for member in tar:
                name = member.name[2:] if member.name.startswith("./") else member.name
                if name in wanted and member.isfile():
                    out = Path(dest_dir) / name
                    out.parent.mkdir(parents=True, exist_ok=True)
                    with tar.extractfile(member) as src, open(out, "wb") as dst:
                        shutil.copyfileobj(src, dst, 1 << 20)
                    wanted.discard(name)
                    if not wanted:
                        break
    finally:
        proc.stdout.close()
        proc.kill()
        proc.wait()
    if wanted:
        raise error(f"not in {deb.name}: {', '.join(sorted(wanted))}")


def extract_model_dir(archive, member, dest_dir, error):
    """Copies `member` of a .zip/.sh3f and the files beside it (materials) into
    dest_dir; returns the model's path there."""
    with zipfile.ZipFile(archive) as z:
        names = {n.lstrip("/"): n for n in z.namelist()}
        real = names.get(member.lstrip("/"))
        if real is None:
            raise error(f"{member} is not in {Path(archive).name}")
        folder = real.rsplit("/", 1)[0] + "/" if "/" in real else ""
        Path(dest_dir).mkdir(parents=True, exist_ok=True)
        for name in z.namelist():
            rest = name[len(folder):]
            if name.startswith(folder) and rest and "/" not in rest:
                with z.open(name) as src, open(Path(dest_dir) / rest, "wb") as dst:
                    shutil.copyfileobj(src, dst, 1 << 20)
        return Path(dest_dir) / real.rsplit("/", 1)[-1]


def prepare_parts(entry, fx, tools, stats, cache_paths, parts_dir):
    """The --parts specs of a generator entry; converts parts not yet cached
    into parts_dir (data/cache/parts). `fx` is data/sources.py (ensure_deb,
    ensure_archive, SceneError, log, TMP)."""
    error = fx.SceneError
    parts_dir.mkdir(parents=True, exist_ok=True)
    todo = [p for p in entry["generator"]["parts"]
            if not (parts_dir / f"{part_key(p)}.ply").exists()]
    # Plain package files of one package: taken out in one pass.
    by_package = {}
    for p in todo:
        if p.get("package") and not p.get("member"):
            by_package.setdefault(p["package"], []).append(p)
    for package, plist in by_package.items():
        deb = fx.ensure_deb(package, stats)
        raw = fx.TMP / f"parts-{package}"
        fx.log(f"  taking {len(plist)} part(s) out of {deb.name} ...")
        extract_many_from_deb(deb, [p["path"] for p in plist], raw, error)
        for p in plist:
            out = parts_dir / f"{part_key(p)}.ply"
            assimp_to_ply(tools, raw / p["path"], out.with_suffix(".part.ply"), error)
            out.with_suffix(".part.ply").replace(out)
        shutil.rmtree(raw, ignore_errors=True)
    specs = []
    for p in entry["generator"]["parts"]:
        out = parts_dir / f"{part_key(p)}.ply"
        if not out.exists():
            if p.get("scene"):
                src = cache_paths.get(p["scene"])
                if src is None:
                    raise error(f"part needs scene '{p['scene']}', which was not obtained")
                assimp_to_ply(tools, src, out.with_suffix(".part.ply"), error)
            else:  # a member of an archive in a package
                archive = fx.ensure_archive(p["package"], p["path"], stats)
                raw = fx.TMP / f"part-{part_key(p)}"
                model = extract_model_dir(archive, p["member"], raw, error)
                assimp_to_ply(tools, model, out.with_suffix(".part.ply"), error)
                shutil.rmtree(raw, ignore_errors=True)
            out.with_suffix(".part.ply").replace(out)
        spec = f"{p['role']}:{p['height']}:{out}"
        if p.get("up_axis", 1) != 1:
            spec += f":{p['up_axis']}"
        specs.append(spec)
    return specs


def part_scenes(entry):
    """Names of the manifest scenes a generator's parts come from."""
    g = entry.get("generator") or {}
    return [p["scene"] for p in g.get("parts", []) if p.get("scene")]


if __name__ == "__main__":
    sys.exit("data/parts.py is used by data/fetch.py")
