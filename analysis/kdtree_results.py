"""The kd-tree runs (results/kdtree.jsonl, written by experiments/run_matrix.py
from //cc/tools:kdrt) as one tidy pandas DataFrame: a row per (scene,
variant), the newest successful record of each.
"""

import json
import os

import pandas as pd

from analysis import provenance

KDTREE_FILE = "kdtree.jsonl"

# The variants, their titles and the report's groups: experiments/matrix.json
# (the one list; the py targets carry it as data).
MATRIX = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))), "experiments", "matrix.json")


def load_matrix(path=MATRIX):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def _groups(matrix):
    """The report's groups: [(name, [variant])], consecutive variants."""
    out, first = [], 0
    for group in matrix["groups"]:
        out.append((group["name"], matrix["variants"][first:first + group["size"]]))
        first += group["size"]
    if first != len(matrix["variants"]):
        raise ValueError("matrix.json: the groups hold %d variants, not the "
                         "%d of variants" % (first, len(matrix["variants"])))
    return out


_MATRIX = load_matrix()
# The report's nine, in the order of its tables.
VARIANTS = list(_MATRIX["variants"])
# Beyond the report (beyond_variants): run by the matrix for the comparison
# with Embree, not part of the report's tables.
BEYOND = list(_MATRIX["beyond_variants"])
TITLES = dict(_MATRIX["titles"])
# The report's three groups of three columns, and their names.
GROUP_NAMES = [name for name, _ in _groups(_MATRIX)]
GROUPS = [variants for _, variants in _groups(_MATRIX)]

# Column -> where kdrt writes it in its record (//cc/tools:kdrt: flat
# top-level names, the tree statistics of cc/kdtree/stats.cc StatsToJson
# among them; "a.b" is member b of object a). Every path is a field of
# cc/tools/kdrt_record.schema.json (record_schema_test), one column each.
# Timing columns are the medians of their timed rounds; the *_runs columns
# hold every round.
FIELDS = {
    "T_B": "T_B", "T_R": "T_R", "perf": "perf_krays",
    "T_B_runs": "T_B_runs", "T_R_runs": "T_R_runs",
    "T_B_warmup": "T_B_warmup", "T_R_warmup": "T_R_warmup",
    # The renderer's fastest mode (kdrt --fast_render; matrix
    # fast_render_variants): packets of 4x4 pixels, shadow rays leaving their
    # origin triangle untested and searched from the light; the same image. Its ratio to Embree is paired
    # per round (Embree T_R / fast T_R).
    "T_R_fast": "fast_render.T_R", "T_R_fast_runs": "fast_render.T_R_runs",
    "fast_ratio": "fast_render.paired_ratio",
    "fast_ratio_runs": "fast_render.paired_ratio_runs",
    # Single rays against single rays (#23's bar), paired per round:
    # Embree's single rays over the fastest of our single-ray modes (the
    # report's rules, the fast mode's secondary rays one ray at a time, and
    # since 2026-12-06 those rays through the BVH over the tree's leaves,
    # whose build from the tree took single_bvh_build_s).
    "T_R_single_origin_runs": "fast_render.single_origin.T_R_runs",
    "T_R_single_bvh_runs": "fast_render.single_bvh.T_R_runs",
    "single_bvh_build_s": "fast_render.single_bvh.build_s",
    # Its nodes' bytes (since 2026-12-07), beside the tree's tree_bytes; and
    # (since session 47, 2026-12-07) its own leaf packets, which it reads
    # instead of the tree's (the kd leaves regrouped: leaf_bvh.h).
    "bvh_bytes": "fast_render.single_bvh.bytes",
    "bvh_packet_bytes": "fast_render.single_bvh.packet_bytes",
    # Our second packet mode (since 2026-12-06): the fast mode's packets
    # through the same BVH (its build: single_bvh_build_s).
    "T_R_packets_bvh_runs": "fast_render.packets_bvh.T_R_runs",
    "single_ratio": "fast_render.single_paired_ratio",
    "single_ratio_runs": "fast_render.single_paired_ratio_runs",
    # Best mode against best mode, paired per round: the faster of Embree's
    # single rays and its packets (rtcIntersect16) over the fastest of ours.
    "best_ratio": "fast_render.best_paired_ratio",
    "best_ratio_runs": "fast_render.best_paired_ratio_runs",
    "embree_packets_T_R_runs": "fast_render.embree_packets.T_R_runs",
    # The same against Embree built with RTC_SCENE_FLAG_ROBUST (kdrt
    # --embree_robust), timed in the same rounds: single rays against the
    # faster of ours, best mode against ours, and the rays exact arithmetic
    # proves it wrong on.
    "robust_single_ratio": "fast_render.embree_robust.single_paired_ratio",
    "robust_single_ratio_runs": "fast_render.embree_robust.single_paired_ratio_runs",
    "robust_best_ratio": "fast_render.embree_robust.best_paired_ratio",
    "robust_best_ratio_runs": "fast_render.embree_robust.best_paired_ratio_runs",
    # Where the gap is, per pass (kdrt_record.h AddPassComparisons): each
    # pass's tracing time alone (less the replay of its mode in the same
    # round), Embree's over ours, paired per round; single rays and packets.
    "camera_single_ratio": "fast_render.passes.camera_single.paired_ratio",
    "camera_single_ratio_runs": "fast_render.passes.camera_single.paired_ratio_runs",
    "shadow_single_ratio": "fast_render.passes.shadow_single.paired_ratio",
    "shadow_single_ratio_runs": "fast_render.passes.shadow_single.paired_ratio_runs",
    "camera_packets_ratio": "fast_render.passes.camera_packets.paired_ratio",
    "camera_packets_ratio_runs": "fast_render.passes.camera_packets.paired_ratio_runs",
    "shadow_packets_ratio": "fast_render.passes.shadow_packets.paired_ratio",
    "shadow_packets_ratio_runs": "fast_render.passes.shadow_packets.paired_ratio_runs",
    # A baseline, not one of our modes (kdrt --triangle_bvh, matrix
    # triangle_bvh_variants; since 2026-12-07): the same kernels over a BVH
    # of whole triangles, timed in the same rounds; Embree's single rays over
    # its single rays, Embree's best mode over its faster lane, its bytes.
    "tri_single_ratio": "fast_render.triangle_bvh.single_paired_ratio",
    "tri_single_ratio_runs": "fast_render.triangle_bvh.single_paired_ratio_runs",
    "tri_best_ratio": "fast_render.triangle_bvh.best_paired_ratio",
    "tri_best_ratio_runs": "fast_render.triangle_bvh.best_paired_ratio_runs",
    "tri_bytes": "fast_render.triangle_bvh.bytes",
    "robust_wrong_primary": "fast_render.embree_robust.wrong.primary",
    "robust_wrong_shadow": "fast_render.embree_robust.wrong.shadow",
    # Its disagreements with our tree, and those of them at a ray's origin
    # (cc/render/compare.h: within rounding of a reported triangle's plane).
    "robust_disagree": "fast_render.embree_robust.disagreements",
    "robust_at_origin": "fast_render.embree_robust.disagreements_at_origin",
    "all_rays_per_s": "all_rays_per_s",
    "N_IT": "N_IT", "N_TR": "N_TR",
    "N_I": "N_I", "N_L": "N_L", "N_TP": "N_TP", "N_AP": "N_AP",
    "N_empty": "N_empty",
    "mem": "mem_report_mb", "tree_bytes": "tree_bytes",
    "R_E": "R_E", "D_max": "D_max", "D_avg": "D_avg",
    "N_CL": "N_CL", "N_PR": "N_PR", "N_lost_planar": "N_lost_planar",
    "sah_cost": "sah_cost",
    "P_hit": "P_hit", "P_miss": "P_miss", "S_hit": "S_hit",
    "S_miss": "S_miss", "n_tri": "n_tri",
    # Embree on the same rays, in the same process, its timed rounds
    # alternating with the kd-tree's: paired_ratio is the median over the
    # rounds of Embree T_R / kd-tree T_R (perf kd over Embree).
    "embree_T_B": "embree.T_B", "embree_T_R": "embree.T_R",
    "embree_T_B_runs": "embree.T_B_runs", "embree_T_R_runs": "embree.T_R_runs",
    # Bytes Embree's build left allocated (its BVH; since 2026-12-06).
    "embree_bvh_bytes": "embree.bvh_bytes",
    "embree_ratio": "embree.paired_ratio",
    "embree_ratio_runs": "embree.paired_ratio_runs",
    "embree_perf": "embree.perf_krays",
    "embree_disagree": "embree.disagreements",
    "embree_grazing": "embree.disagreements_grazing",
    "embree_other": "embree.disagreements_other",
    "embree_at_origin": "embree.disagreements_at_origin",
    "embree_t_guard": "embree.disagreements_t_guard",
    # Judged in exact arithmetic (cc/render/compare.h): the kd-tree is the
    # reference tracer of kdrt's comparison, Embree the other.
    "kd_wrong": "disagreements.reference_wrong",
    "embree_wrong": "disagreements.other_wrong",
    "embree_rays_per_s": "embree.all_rays_per_s",
    "threads": "threads", "repeats": "repeats",
    "repeat_budget_s": "repeat_budget_s",
    # Added by experiments/run_matrix.py (the schema's run_matrix section).
    "job": "job", "concurrent_jobs": "concurrent_jobs",
}


def present(value):
    """True for a number in a frame cell: not None (field absent) and not NaN
    (pandas' fill for a missing cell)."""
    return value is not None and value == value


def _get(rec, path):
    cur = rec
    for part in path.split("."):
        if not isinstance(cur, dict) or part not in cur:
            return None
        cur = cur[part]
    return cur


def field(rec, name):
    value = _get(rec, FIELDS[name])
    return None if isinstance(value, dict) else value


def latest(records):
    """{(scene, preset): the newest successful record} (results files are
    append-only: a rerun appends)."""
    out = {}
    for rec in records:
        if rec.get("ok") and rec.get("scene") and rec.get("preset"):
            out[(rec["scene"], rec["preset"])] = rec
    return out


def frame(records, manifest):
    """DataFrame indexed by (scene, variant) with every FIELDS column plus
    order (manifest order), report_scene and provenance (the record's
    provenance object, analysis/provenance.py; None when unknown)."""
    order = {s["name"]: i for i, s in enumerate(manifest)}
    report = {s["name"]: s.get("report_scene") for s in manifest}
    rows = []
    for (scene, variant), rec in latest(records).items():
        row = {"scene": scene, "variant": variant,
               "order": order.get(scene, len(order)),
               "report_scene": report.get(scene),
               "provenance": provenance.of(rec)}
        for name in FIELDS:
            row[name] = field(rec, name)
        rows.append(row)
    if not rows:
        return pd.DataFrame(columns=["scene", "variant", "order",
                                     "report_scene", "provenance"]
                            + list(FIELDS))
    df = pd.DataFrame(rows).sort_values(["order", "scene"])
    return df.set_index(["scene", "variant"])


def scenes_in_order(df):
    if df.empty:
        return []
    seen = []
    for scene in df.reset_index().sort_values(["order", "scene"])["scene"]:
        if scene not in seen:
            seen.append(scene)
    return seen
