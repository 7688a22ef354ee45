"""The Markdown tables of experiments/bench.py about structure: what the
packet kernel did per packet (packets_summary: its steps and the lanes each
carried), what the kd-tree's structure costs against a BVH of whole
triangles traced by the same kernels (triangle_bvh_summary), and each tree's
bytes per triangle against Embree's BVH (memory_summary). The timing
helpers are bench_tables.py's.
"""
import statistics

from analysis import tree_memory  # the bytes our best mode reads: one rule
from bench_tables import EMBREE_ALL, TRI_BVH_MODES
from bench_tables import one_thread_by_size, per_round_ratio, tracing_runs


def packets_summary(records):
    """What the packet kernel did in one untimed render per packet variant
    (render_bench's packet_counts; one row per scene, variant and query:
    closest hit for the primary rays, any hit for the shadow rays): the
    packets that reached the tree, per packet its steps (inner nodes, leaves,
    vector triangle tests) and the lanes each carried, and per ray N_TR and
    N_IT, which every lane of the kd-tree's packets reproduces from its
    single ray (kd_bvh_packet: the BVH's nodes as inner steps and N_TR, per
    lane)."""
    out = ["| scene | variant | kernel | query | packets | inner steps / packet "
           "| leaf steps / packet | triangle steps / packet | lanes per inner step "
           "| lanes per triangle step | N_TR / ray | N_IT / ray |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in one_thread_by_size(records):
        for variant, c in r.get("packet_counts", {}).items():
            for query in ("closest", "any"):
                q = c[query]
                p, lanes, ray = q["per_packet"], q["lanes_per_step"], q["per_ray"]
                out.append("| %s | %s | %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | "
                           "%.1f |" % (r["scene"], variant, c["kernel"], query,
                                       format(q["packets"], ","), p["inner_steps"],
                                       p["leaf_steps"], p["triangle_steps"], lanes["inner"],
                                       lanes["triangle"], ray["N_TR"], ray["N_IT"]))
    return "\n".join(out)


def triangle_bvh_summary(records):
    """What the kd-tree's structure costs (one thread, rows with the
    baseline's variants): the best mode of our kd-tree (every "kd" tracer, as
    targets_summary) and of the same kernels over a BVH of whole triangles
    (tri_bvh, tri_bvh_packet; cc/kdtree/triangle_bvh.h) against Embree's
    best mode, paired per round; their packets' tracing time alone per pass
    against Embree's packets (kd_bvh_packet and tri_bvh_packet, as
    passes_summary); and the bytes each reads per triangle (the BVH over the
    kd-tree's leaves with its own leaf packets, before session 47 the tree
    and that BVH's nodes; the triangle BVH; Embree's BVH). What the baseline
    gains over the kd-tree is the kd-tree's structure; what it still lacks
    against Embree is the kernel. "" when no row has the baseline."""
    out = ["| scene | triangles | best mode / Embree's: kd-tree | best mode / Embree's: "
           "triangle BVH | camera packets: kd-tree, triangle BVH | shadow packets: kd-tree, "
           "triangle BVH | bytes / triangle: kd-tree, triangle BVH, Embree |",
           "|---|---|---|---|---|---|---|"]
    columns = [[] for _ in range(6)]
    for r in one_thread_by_size(records):
        t = r["tracers"]
        if not any(n in t for n in TRI_BVH_MODES):
            continue
        ours = [n for n in t if n.startswith("kd") and not n.endswith("_twice")]
        tri = [n for n in t if n in TRI_BVH_MODES]
        values = [per_round_ratio(t, EMBREE_ALL, ours), per_round_ratio(t, EMBREE_ALL, tri)]
        for key in ("primary_s_runs", "secondary_s_runs"):
            for name in ("kd_bvh_packet", "tri_bvh_packet"):
                values.append(per_round_ratio(t, ("embree_packet",), (name,), tracing_runs(key)))
        for k, value in enumerate(values):
            if value is not None:
                columns[k].append(value[0])
        fmt = lambda v: "-" if v is None else "%.2f [%.2f..%.2f]" % v  # noqa: E731
        cells = [fmt(values[0]), fmt(values[1]), "%s, %s" % (fmt(values[2]), fmt(values[3])),
                 "%s, %s" % (fmt(values[4]), fmt(values[5]))]
        n = r["n_tri"]
        sizes = [tree_memory.best_mode_bytes(r), r.get("tri_bvh_bytes"),
                 r.get("embree_bvh_bytes")]
        cells.append(", ".join("-" if not b else "%.0f" % (b / n) for b in sizes))
        out.append("| %s | %s | %s |" % (r["scene"], format(n, ","), " | ".join(cells)))
    if len(out) == 2:
        return ""
    names = ("Best mode, kd-tree", "Best mode, triangle BVH", "Camera packets, kd-tree",
             "Camera packets, triangle BVH", "Shadow packets, kd-tree",
             "Shadow packets, triangle BVH")
    for name, values in zip(names, columns):
        if values:
            out.append("")
            out.append("%s, Embree's over ours over %d rows: median %.2f, range %.2f to %.2f, "
                       "%d at 1.0 or more." % (name, len(values), statistics.median(values),
                                               min(values), max(values),
                                               sum(v >= 1.0 for v in values)))
    return "\n".join(out)


def memory_summary(records):
    """Each scene's tree against Embree's BVH, in bytes per triangle
    (render_bench's tree_bytes, its nodes and leaf packets, and
    embree_bvh_bytes, what Embree's build left allocated by its memory
    monitor; records since 2026-12-06). One row per scene and preset with
    one thread; records without Embree's bytes are left out."""
    out = ["| scene | triangles | preset | tree, bytes / triangle | Embree's BVH, bytes / triangle "
           "| tree / Embree's |",
           "|---|---|---|---|---|---|"]
    for r in one_thread_by_size(records):
        ours, theirs = r.get("tree_bytes"), r.get("embree_bvh_bytes")
        if not ours or not theirs:
            continue
        n = r["n_tri"]
        out.append("| %s | %s | %s | %.0f | %.0f | %.2f |" % (
            r["scene"], format(n, ","), r["preset"], ours / n, theirs / n, ours / theirs))
    return "\n".join(out) if len(out) > 2 else ""
