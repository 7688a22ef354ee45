"""Small fixture inputs for the analysis tests (written to a temp dir).

These are made-up numbers for tests only; they are never results.
"""

import json
import os

MANIFEST = {"scenes": [
    {"name": "bunny", "report_scene": None, "report_name": None,
     "kind": "package", "package": "fixture-meshes", "path": "bunny.ply",
     "licence": "CC0 & free", "expected_triangles": 69666,
     "profiles": ["test", "quick", "standard", "full"]},
    {"name": "armadillo", "report_scene": 2, "report_name": "Armadillo",
     "kind": "npm", "package": "fixture_armadillo", "path": "a.ply",
     "licence": "Stanford 100% research", "expected_triangles": 345944,
     "profiles": ["quick", "standard", "full"]},
    {"name": "not_fetched", "report_scene": 3, "report_name": None,
     "kind": "url", "package": None, "path": "x.obj", "licence": "CC-BY",
     "expected_triangles": 7219045, "profiles": ["full"]},
    {"name": "city_gen", "report_scene": 5, "report_name": None,
     "kind": "generator", "package": "gen_city", "path": "city.obj",
     "licence": "MIT #2", "expected_triangles": 68000,
     "profiles": ["quick", "standard", "full"]},
    {"name": "suzanne", "report_scene": 18, "report_name": "suzanne",
     "kind": "blender", "package": None, "path": "suzanne.obj",
     "licence": "GPL", "expected_triangles": None,
     "profiles": ["test", "quick", "standard", "full"]},
    {"name": "broken_scene", "report_scene": None, "report_name": None,
     "kind": "generator", "package": "gen_broken", "path": "b.obj",
     "licence": "CC0", "expected_triangles": 10,
     "profiles": ["quick", "standard", "full"]},
]}


def record(scene, n_tri=None, ok=True, error=None, profile="quick"):
    rec = {"scene": scene, "mesh": "/fixture/%s.obj" % scene,
           "mesh_bytes": 1000, "ok": ok, "profile": profile}
    if ok:
        rec.update(n_tri=n_tri, skipped_faces=0, dropped_degenerate=0,
                   dropped_nonfinite=0, load_s=0.01, from_cache=False,
                   bounds=[[0, 0, 0], [1, 1, 1]])
    else:
        rec.update(error=error or "boom", returncode=1)
    return rec


RECORDS = [
    record("bunny", 69666),
    record("armadillo", 345944),
    # a failure followed by a success: the success wins
    record("city_gen", ok=False, error="first try failed"),
    record("city_gen", 68010),
    record("suzanne", 968),
    record("broken_scene", ok=False,
           error="warning: x\nscene_info: bad_file #3 at 100%"),
]

MACHINE = {
    "cpu_model": "Fixture CPU @ 1.00GHz", "cpu_count": 8, "memory_gib": 16.0,
    "os": "Fixture OS", "compiler": "g++ (Fixture) 12.2.0",
    "git_commit": "0123456789abcdef0123456789abcdef01234567",
    "git_dirty": False, "recorded_at": "2024-12-16T10:00:00+00:00",
    "profile": "quick",
}


def write_fixture(root, manifest=MANIFEST, records=RECORDS, machine=MACHINE):
    """Writes ROOT/manifest.json and ROOT/results/{scenes.jsonl,machine.json};
    returns (results_dir, manifest_path)."""
    results = os.path.join(root, "results")
    os.makedirs(results, exist_ok=True)
    manifest_path = os.path.join(root, "manifest.json")
    with open(manifest_path, "w", encoding="utf-8") as f:
        json.dump(manifest, f)
    with open(os.path.join(results, "scenes.jsonl"), "w",
              encoding="utf-8") as f:
        for rec in records:
            f.write(json.dumps(rec) + "\n")
    if machine is not None:
        with open(os.path.join(results, "machine.json"), "w",
                  encoding="utf-8") as f:
            json.dump(machine, f)
    return results, manifest_path
