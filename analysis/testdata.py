"""Small fixture inputs for the analysis tests (written to a temp dir).

These are made-up numbers for tests only; they are never results.
"""

import json
import os
import statistics
import tempfile
import unittest

from analysis import context
from analysis import kdtree_results as kr

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
# them (declared in cc/tools/kdrt_record.schema.json; record_schema_test
# validates these fixtures against it, kdrt_records_test real records): flat
# statistics (cc/kdtree/stats.cc StatsToJson), "embree" and "fast_render"
# objects (null when not run), one "provenance" object (cc/base/provenance.h),
# and run_matrix.py's "ok", "job", "profile", "wall_s", "node", "backend",
# "concurrent_jobs".

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


def cost_traversal(counts):
    """kdrt's "traversal" object that a cost image (a (height, width, 3, 3)
    array of rays, inner visits, triangle tests per kind: cc/render/
    cost_image.h) sums to, as the run that wrote it would record it."""
    out = {}
    for k, kind in enumerate(("primary", "shadow", "ao")):
        rays = int(counts[:, :, k, 0].sum())
        out[kind] = {"rays": rays,
                     "N_IT": float(counts[:, :, k, 2].sum()) / rays if rays else 0.0,
                     "N_TR": float(counts[:, :, k, 1].sum()) / rays if rays else 0.0,
                     "leaves": 3.0}
    return out


def _effects(rays, seconds, rounds=1):
    def one(kind):
        t = seconds if kind != "ao" else 0.0
        return {"rays": rays if kind != "ao" else 0, "seconds": t,
                "seconds_runs": [t] * rounds}
    return {kind: one(kind) for kind in ("primary", "shadow", "ao")}


def _config(max_depth=24, max_leaf_size=8):
    return {"max_depth": max_depth, "max_leaf_size": max_leaf_size,
            "use_binning": True, "use_driving_axis": True, "bins": 16,
            "use_clipping": True, "use_pruning": True,
            "cast_shadow_rays": True, "seed_compatible": False}


def disagreements(**over):
    """kdrt's "disagreements" object with no disagreement (override the
    totals: reference_wrong=4, ...)."""
    kind = {k: 0 for k in ("rays", "total", "grazing", "at_origin", "t_guard",
                           "other", "hit_miss", "t_differs",
                           "reference_wrong", "other_wrong")}
    out = dict(kind, rays=940000, **over)
    out.update(primary=dict(kind), shadow=dict(kind), ao=dict(kind))
    return out


def embree(t_r=0.2, ratios=None, t_b=0.1, **over):
    """kdrt's "embree" object: Embree's warm-up apart, then its timed rounds
    (paired_ratio_runs: Embree T_R / kd T_R per round; default one round)."""
    ratios = [1.0] if ratios is None else list(ratios)
    emb = {"quality": "medium", "timed": True, "T_B": t_b, "T_B_runs": [t_b] * len(ratios),
           "T_B_warmup": t_b, "bvh_bytes": 64000, "T_R": t_r, "T_R_runs": [t_r] * len(ratios),
           "T_R_warmup": t_r, "perf_krays": 640.0 / t_r,
           "all_rays_per_s": 940000 / t_r, "P_hit": 300, "P_miss": 340,
           "S_hit": 100, "S_miss": 200,
           "effects": _effects(640000, t_r / 2, len(ratios)),
           "disagreements_grazing": 0, "disagreements_at_origin": 0,
           "disagreements_t_guard": 0, "disagreements_other": 0,
           "disagreements": 0, "paired_ratio_runs": ratios,
           "paired_ratio": statistics.median(ratios),
           "perf_ratio_kd_over_embree": statistics.median(ratios)}
    emb.update(over)
    return emb


def embree_untimed(**over):
    """kdrt's "embree" object with --noembree_rounds: built once, untimed,
    for the comparison alone."""
    emb = embree()
    emb.update({"timed": False, "T_B": None, "T_B_runs": [], "T_R": None,
                "T_R_runs": [], "T_R_warmup": None, "perf_krays": None,
                "all_rays_per_s": None, "P_hit": None, "P_miss": None,
                "S_hit": None, "S_miss": None, "effects": None,
                "paired_ratio": None, "perf_ratio_kd_over_embree": None})
    emb.update(over)
    return emb


def _base_record(scene, preset):
    """kdrt's fields, in kdrt's order, with made-up numbers."""
    return {"scene": scene, "mesh": "/fixture/%s.obj" % scene, "n_tri": 1000,
            "load_s": 0.01,
            "dropped_at_load": {"nonfinite": 0, "degenerate": 0,
                                "point_line_faces": 0},
            "preset": preset, "label": preset, "env_file": None,
            "overrides": [], "config": _config(), "env": "KDTree { }",
            "view_source": "auto", "view": "fixture", "width": 800,
            "height": 800, "lights": 1, "threads": 1, "repeats": 1,
            "repeat_budget_s": 0,
            "timing": {"method": "fixture", "rounds": 1, "lock_wait_s": 0.0,
                       "phases_s": {"load": 0.01, "timed renders": 1.0}},
            "T_B": 0.5, "T_B_runs": [0.5], "T_B_warmup": 0.5, "T_R": 1.0,
            "T_R_runs": [1.0], "T_R_warmup": 1.0, "perf_krays": 640.0,
            "all_rays_per_s": 940000.0, "rays_total": 940000, "N_IT": 10.0,
            "N_TR": 20.0,
            "traversal": {"primary": _traversal(640000),
                          "shadow": _traversal(300000), "ao": _traversal(0)},
            "counting_mismatches": 0, "N_I": 99, "N_L": 100, "N_empty": 10,
            "N_TP": 500, "N_AP": 5.0, "R_E": 0.1, "D_max": 24, "D_avg": 18.0,
            "N_CL": 0, "N_PR": 0, "N_lost_planar": 0, "mem_report_mb": 0.01,
            "tree_bytes": 4000, "build_peak_bytes": 8000, "sah_cost": 50.0,
            "invalid_leaf_boxes": 0, "P_hit": 300, "P_miss": 340,
            "S_hit": 100, "S_miss": 200, "AO_hit": 0, "AO_miss": 0,
            "effects": _effects(640000, 0.5), "image": None,
            "image_fnv64": "0123456789abcdef", "embree": None,
            "disagreements": None, "perf_ratio_kd_over_embree": None,
            "fast_render": None, "provenance": provenance()}


def matrix_fields(scene, preset, profile="quick", concurrent_jobs=1):
    """What experiments/run_matrix.py adds to a successful kdrt record."""
    return {"ok": True, "job": [scene, preset, 1, 1, "off", TREE],
            "profile": profile, "wall_s": 2.0, "node": {"host": "fixture"},
            "backend": "local", "concurrent_jobs": concurrent_jobs}


def accuracy_fields(scene, knob, step, options=None):
    """What experiments/run_accuracy.py adds to a successful kdrt record."""
    return {"ok": True, "job": [scene, step, 1, TREE], "knob": knob,
            "step": step, "options": options or {}, "profile": "quick",
            "wall_s": 2.0, "node": {"host": "fixture"}, "concurrent_jobs": 2}


def failure(scene, preset, error="boom"):
    """run_matrix.py's record of a failed kdrt run."""
    return {"ok": False, "job": [scene, preset, 1, 1, "off", TREE],
            "scene": scene, "preset": preset, "profile": "quick",
            "returncode": 1, "wall_s": 0.1, "command": ["kdrt"],
            "error": error, "backend": "local", "concurrent_jobs": 1}


def kdrt_record(scene, preset, added=None, **over):
    """One successful record: kdrt's fields and a runner's (`added`; default
    run_matrix.py's, matrix_fields) with made-up numbers; keyword arguments
    replace top-level members (T_B, N_CL, embree=embree(...), ...). A T_B or
    T_R given without its runs gets runs of that one value; embree=...
    without disagreements gets kdrt's object of none (and the top-level perf
    ratio of its paired median)."""
    rec = _base_record(scene, preset)
    rec.update(matrix_fields(scene, preset) if added is None else added)
    for key in ("T_B", "T_R"):
        if key in over and key + "_runs" not in over:
            over[key + "_runs"] = [over[key]]
    rec.update(over)
    if isinstance(rec["embree"], dict):
        rec["perf_ratio_kd_over_embree"] = rec["embree"].get("paired_ratio")
        if rec["disagreements"] is None:
            rec["disagreements"] = disagreements()
    return rec


def fast_render(ratios, t_r=0.16, best=None, robust=None, single=None, passes=None,
                tri=None):
    """kdrt's "fast_render" object with its paired ratios to Embree (and,
    with `best`, Embree's packets and the best-mode ratios per round; with
    `robust`, (single-ray ratios, best-mode ratios, wrong shadow rays) of
    Embree built with RTC_SCENE_FLAG_ROBUST; with `single`, our other
    single-ray modes and Embree's single rays over the fastest of ours; with
    `passes`, {pass: [ratio per round]} for the passes camera_single,
    shadow_single, camera_packets and shadow_packets; with `tri`, (single-ray
    ratios, best-mode ratios, bytes) of the baseline over whole triangles)."""
    ratios = list(ratios)
    out = {"T_R": t_r, "T_R_runs": [t_r] * len(ratios), "primary_s": t_r / 2,
           "shadow_s": t_r / 2, "packet_kernel": "AVX3"}
    if single is not None:
        out["single_origin"] = {"T_R": t_r, "T_R_runs": [t_r] * len(ratios),
                                "primary_s": t_r / 2, "shadow_s": t_r / 2}
        out["single_bvh"] = {"T_R": t_r, "T_R_runs": [t_r] * len(ratios),
                             "primary_s": t_r / 2, "shadow_s": t_r / 2, "build_s": 0.001,
                             "bytes": 2560, "packet_bytes": 6400}
        out["packets_bvh"] = {"T_R": t_r, "T_R_runs": [t_r] * len(ratios),
                              "primary_s": t_r / 2, "shadow_s": t_r / 2, "build_s": 0.001,
                              "bytes": 2560, "packet_bytes": 6400}
    out.update({"paired_ratio_runs": ratios, "paired_ratio": statistics.median(ratios)})
    if single is not None:
        out["single_paired_ratio_runs"] = list(single)
        out["single_paired_ratio"] = statistics.median(single)
    if best is not None:
        best = list(best)
        out["embree_packets"] = {"T_R": t_r, "T_R_runs": [t_r] * len(best),
                                 "primary_s": t_r / 2, "shadow_s": t_r / 2,
                                 "paired_ratio_runs": best,
                                 "paired_ratio": statistics.median(best)}
        out["best_paired_ratio_runs"] = best
        out["best_paired_ratio"] = statistics.median(best)
    if robust is not None:
        robust_single, best_r, wrong = robust
        n = len(robust_single)
        out["embree_robust"] = {
            "T_R": t_r, "T_R_runs": [t_r] * n, "packets_T_R": t_r,
            "packets_T_R_runs": [t_r] * n, "single_paired_ratio_runs": list(robust_single),
            "single_paired_ratio": statistics.median(robust_single),
            "best_paired_ratio_runs": list(best_r),
            "best_paired_ratio": statistics.median(best_r), "disagreements": wrong,
            "disagreements_at_origin": wrong - 1,
            "wrong": {"primary": 0, "shadow": wrong, "ao": 0}}
    if tri is not None:
        tri_single, tri_best, tri_bytes = tri
        lane = {"T_R": t_r, "T_R_runs": [t_r] * len(tri_single), "primary_s": t_r / 2,
                "shadow_s": t_r / 2, "primary_s_runs": [t_r / 2] * len(tri_single),
                "shadow_s_runs": [t_r / 2] * len(tri_single)}
        out["triangle_bvh"] = {
            "single": dict(lane), "packets": dict(lane), "build_s": 0.01, "bytes": tri_bytes,
            "single_paired_ratio_runs": list(tri_single),
            "single_paired_ratio": statistics.median(tri_single),
            "best_paired_ratio_runs": list(tri_best),
            "best_paired_ratio": statistics.median(tri_best)}
    if passes is not None:
        n = len(ratios)
        out["passes"] = {
            name: {"paired_ratio": statistics.median(runs) if runs else None,
                   "paired_ratio_runs": list(runs)}
            for name, runs in passes.items()}
        for key in ("replay_primary_s_runs", "replay_shadow_s_runs",
                    "replay_packets_primary_s_runs", "replay_packets_shadow_s_runs"):
            out["passes"][key] = [t_r / 8] * n
    return out


def write_kdtree(results_dir, records):
    """Writes RESULTS/kdtree.jsonl (appending)."""
    with open(os.path.join(results_dir, "kdtree.jsonl"), "a",
              encoding="utf-8") as f:
        for rec in records:
            f.write(json.dumps(rec) + "\n")


NINE = kr.VARIANTS  # the report's nine (experiments/matrix.json)
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
    recs.append(failure("alpha", "binning-8"))
    write_kdtree(results, recs)
    manifest = os.path.join(root, "manifest.json")
    with open(manifest, "w", encoding="utf-8") as f:
        json.dump({"scenes": [{"name": "gamma"}, {"name": "alpha"},
                              {"name": "beta"}]}, f)
    return results, manifest


class KdtreeFixtureTest(unittest.TestCase):
    """A test case on kdtree_fixture's results: self.ctx reads them and writes
    to self.out; read(name) returns a file written there."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        results, manifest = kdtree_fixture(self.tmp.name)
        self.out = os.path.join(self.tmp.name, "out")
        os.makedirs(self.out)
        self.ctx = context.Context(results, manifest, self.out)

    def tearDown(self):
        self.tmp.cleanup()

    def read(self, name):
        with open(os.path.join(self.out, name)) as f:
            return f.read()
