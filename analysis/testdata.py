"""Small fixture inputs for the analysis tests (written to a temp dir).

These are made-up numbers for tests only; they are never results.
"""

import json
import os
import statistics

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


# --- kdrt records (results/kdtree.jsonl), in the shape //cc/tools:kdrt writes
# them: flat statistics (cc/kdtree/stats.cc StatsToJson), "embree" and
# "fast_render" objects (null when not run), one "provenance" object
# (cc/base/provenance.h), and run_matrix.py's "ok", "job", "concurrent_jobs".

COMMIT = "0123456789abcdef0123456789abcdef01234567"
TREE = "89abcdef0123456789abcdef0123456789abcdef"


def provenance(**over):
    """A provenance object of an optimised, clean build (override any member)."""
    prov = {"commit": COMMIT, "dirty": False, "source_tree": TREE,
            "compilation_mode": "opt", "optimized": True, "ndebug": True,
            "avx2": True, "avx512f": False, "fma": True, "timing_build": True,
            "compiler": "12.2.0", "cpu_model": "Fixture CPU @ 1.00GHz",
            "cores": 2, "timing_lock": "/tmp/kdtree-timing.lock",
            "timed_beside": 0, "timestamp_utc": "2026-12-03T02:00:00Z"}
    prov.update(over)
    return prov


def _traversal(rays):
    return {"rays": rays, "N_IT": 10.0, "N_TR": 20.0, "leaves": 3.0}


def _effects(rays, seconds):
    return {kind: {"rays": rays if kind != "ao" else 0,
                   "seconds": seconds if kind != "ao" else 0.0}
            for kind in ("primary", "shadow", "ao")}


def embree(t_r=0.2, ratios=None, t_b=0.1, **over):
    """kdrt's "embree" object: Embree's warm-up apart, then its timed rounds
    (paired_ratio_runs: Embree T_R / kd T_R per round; default one round)."""
    ratios = [1.0] if ratios is None else list(ratios)
    emb = {"quality": "medium", "T_B_warmup": t_b, "T_R_warmup": t_r,
           "T_B": t_b, "T_B_runs": [t_b] * len(ratios), "T_R": t_r,
           "T_R_runs": [t_r] * len(ratios), "perf_krays": 640.0 / t_r,
           "all_rays_per_s": 940000 / t_r, "P_hit": 300, "P_miss": 340,
           "S_hit": 100, "S_miss": 200, "effects": _effects(640000, t_r / 2),
           "disagreements": 0, "disagreements_grazing": 0,
           "disagreements_at_origin": 0, "disagreements_t_guard": 0,
           "disagreements_other": 0, "paired_ratio_runs": ratios,
           "paired_ratio": statistics.median(ratios)}
    emb.update(over)
    return emb


def kdrt_record(scene, preset, **over):
    """One successful kdrt record with made-up numbers; keyword arguments
    replace top-level members (T_B, N_CL, embree=embree(...), ...). A T_B or
    T_R given without its runs gets runs of that one value."""
    rec = {"scene": scene, "mesh": "/fixture/%s.obj" % scene, "n_tri": 1000,
           "load_s": 0.01, "preset": preset, "label": preset, "env_file": None,
           "overrides": [], "config": {"max_depth": 24, "max_leaf_size": 8},
           "env": "KDTree { }", "view_source": "auto", "view": "fixture",
           "width": 800, "height": 800, "lights": 1, "threads": 1,
           "repeats": 1, "repeat_budget_s": 0, "T_B_warmup": 0.5,
           "T_R_warmup": 1.0, "T_B": 0.5, "T_B_runs": [0.5], "T_R": 1.0,
           "T_R_runs": [1.0], "perf_krays": 640.0, "all_rays_per_s": 940000.0,
           "rays_total": 940000, "N_IT": 10.0, "N_TR": 20.0,
           "traversal": {"primary": _traversal(640000),
                         "shadow": _traversal(300000), "ao": _traversal(0)},
           "counting_mismatches": 0, "N_I": 99, "N_L": 100, "N_empty": 10,
           "N_TP": 500, "N_AP": 5.0, "R_E": 0.1, "D_max": 24, "D_avg": 18.0,
           "N_CL": 0, "N_PR": 0, "N_lost_planar": 0, "mem_report_mb": 0.01,
           "tree_bytes": 4000, "build_peak_bytes": 8000, "sah_cost": 50.0,
           "invalid_leaf_boxes": 0, "P_hit": 300, "P_miss": 340, "S_hit": 100,
           "S_miss": 200, "AO_hit": 0, "AO_miss": 0,
           "effects": _effects(640000, 0.5), "image": None,
           "image_fnv64": "0123456789abcdef", "embree": None,
           "disagreements": None, "perf_ratio_kd_over_embree": None,
           "fast_render": None, "provenance": provenance(),
           "ok": True, "job": [scene, preset, 1, 1, "off", TREE],
           "concurrent_jobs": 1}
    for key in ("T_B", "T_R"):
        if key in over and key + "_runs" not in over:
            over[key + "_runs"] = [over[key]]
    rec.update(over)
    if isinstance(rec["embree"], dict):
        rec["perf_ratio_kd_over_embree"] = rec["embree"].get("paired_ratio")
    return rec


def fast_render(ratios, t_r=0.16):
    """kdrt's "fast_render" object with its paired ratios to Embree."""
    ratios = list(ratios)
    return {"T_R": t_r, "T_R_runs": [t_r] * len(ratios), "primary_s": t_r / 2,
            "shadow_s": t_r / 2, "paired_ratio_runs": ratios,
            "paired_ratio": statistics.median(ratios)}


def write_kdtree(results_dir, records):
    """Writes RESULTS/kdtree.jsonl (appending)."""
    with open(os.path.join(results_dir, "kdtree.jsonl"), "a",
              encoding="utf-8") as f:
        for rec in records:
            f.write(json.dumps(rec) + "\n")


NINE = ["median-16-2", "median-24-2", "median-24-8", "binning-8-driving",
        "binning-8", "binning-32", "clipping", "pruning", "clipping-pruning"]
# Per variant, what differs from kdrt_record's defaults in kdtree_fixture.
KDTREE_OVERRIDES = {
    "median-16-2": {"N_IT": 100.0, "N_TR": 5.0, "N_AP": 40.0},
    "clipping": {"N_CL": 3000, "repeats": 5, "repeat_budget_s": 30,
                 "T_B_runs": [0.5, 0.5], "T_R_runs": [1.0] * 5,
                 "concurrent_jobs": 2},
    # Clipping-pruning renders clearly slower than pruning: the ranges of
    # their three rounds are apart.
    "pruning": {"N_PR": 900, "T_R": 0.8, "T_R_runs": [0.78, 0.8, 0.82]},
    "clipping-pruning": {"N_PR": 100, "N_CL": 2000, "T_R": 0.9,
                         "T_R_runs": [0.88, 0.9, 0.92]},
}


def kdtree_fixture(root):
    """ROOT/results/kdtree.jsonl (the nine variants on scenes alpha, beta,
    gamma, and one failure) and ROOT/manifest.json (gamma, alpha, beta);
    returns (results_dir, manifest_path)."""
    results = os.path.join(root, "results")
    os.makedirs(results, exist_ok=True)
    recs = [kdrt_record(scene, v, **dict(KDTREE_OVERRIDES.get(v, {})))
            for scene in ("alpha", "beta", "gamma") for v in NINE]
    recs.append({"ok": False, "scene": "alpha", "preset": "binning-8",
                 "job": ["alpha", "binning-8", 1, 1, "off", TREE],
                 "error": "boom", "returncode": 1})
    write_kdtree(results, recs)
    manifest = os.path.join(root, "manifest.json")
    with open(manifest, "w", encoding="utf-8") as f:
        json.dump({"scenes": [{"name": "gamma"}, {"name": "alpha"},
                              {"name": "beta"}]}, f)
    return results, manifest
