"""Where a single ray's time goes, by what the ray does (render_bench
--classes, cc/bench/ray_classes.h): per scene and class of the recorded rays
(camera rays that reach no node of the tree, camera rays that reach it and
hit nothing, camera hits, shadow rays), our single rays and Embree's, each
class traced alone in a tight loop, in the same rounds. Times are ns per
ray, medians over the rounds; Embree's speed over ours is paired per round,
median [lowest..highest]. A class's share of the rays says how much its
ratio weighs in a render's. Traced alone, a class does not see the render's
mix of caches and predictors, so these are a diagnosis; the targets are
render_bench's rounds."""
import statistics

import bench_tables

# Our single-ray variant: the first of these a record has (kd_bvh, the BVH
# over the kd-tree's leaves, since it is our fastest single-ray mode; then
# the kd-tree's own traversal).
OURS = ("kd_bvh", "kd_origin", "kd")
THEIRS = "embree"


def pooled(classes):
    """A class table's per-round times, medians and Embree's paired ratios
    recomputed from its ns_runs (bench_merge pools the runs of several
    processes)."""
    out = {}
    for name, c in classes.items():
        runs = c.get("ns_runs", {})
        ours = next((n for n in OURS if n in runs), None)
        if ours is None or THEIRS not in runs:
            continue
        ratios = [e / o for e, o in zip(runs[THEIRS], runs[ours])]
        out[name] = {"rays": c["rays"], "ours": ours,
                     "ours_ns": statistics.median(runs[ours]),
                     "theirs_ns": statistics.median(runs[THEIRS]),
                     "ratios": ratios}
    return out


def overview(tables):
    """Per class over the scenes: the median share of the rays and the median
    [lowest..highest] of the scenes' paired ratios."""
    out = ["| class | ours | scenes | share of the rays, median | Embree's over ours, median "
           "of the scenes [lowest..highest] |", "|---|---|---|---|---|"]
    keys = []
    for table in tables:
        keys += [(n, c["ours"]) for n, c in table.items() if (n, c["ours"]) not in keys]
    for name, ours in keys:
        rows = [(t[name], sum(c["rays"] for c in t.values())) for t in tables
                if name in t and t[name]["ours"] == ours]
        ratios = [statistics.median(c["ratios"]) for c, _ in rows]
        share = statistics.median([100.0 * c["rays"] / total for c, total in rows])
        out.append("| %s | %s | %d | %.0f %% | %s |" % (
            name, ours, len(rows), share, bench_tables.median_range(ratios)))
    return out


def classes_summary(records):
    """Per class, its median over the scenes; then one row per one-thread
    record with ray classes, and class."""
    one_thread = [r for r in bench_tables.one_thread_by_size(records) if r.get("ray_classes")]
    tables = [pooled(r["ray_classes"]["classes"]) for r in one_thread]
    if not any(tables):
        return ""
    out = overview([t for t in tables if t]) + [""]
    out += ["| scene | triangles | class | ours | rays | share | ours, ns / ray | Embree, ns / ray "
            "| Embree's over ours |", "|---|---|---|---|---|---|---|---|---|"]
    for r, table in zip(one_thread, tables):
        total = sum(c["rays"] for c in table.values())
        for name, c in table.items():
            out.append("| %s | %s | %s | %s | %s | %.0f %% | %.1f | %.1f | %s |" % (
                r["scene"], format(r["n_tri"], ","), name, c["ours"], format(c["rays"], ","),
                100.0 * c["rays"] / total, c["ours_ns"], c["theirs_ns"],
                bench_tables.median_range(c["ratios"])))
    return "\n".join(out)
