"""Memory of the finished trees: bytes per triangle (issue 23: no copy of a
triangle beside the one the traversal reads, aiming at 64 bytes a triangle
or less for our fastest tree).

A finished tree (cc/kdtree/tree.h) holds its 8-byte nodes and, per leaf, its
triangles in packets of four (160 bytes a packet: the vertices and the
indices, cc/kdtree/leaf_layout.h); the record's tree_bytes is their sum. A
leaf stores the triangles it references, so a triangle that several leaves
reference (clipping) is stored once per reference, and the bytes follow
N_TP, the references, more than N_tri. Records written before 4c5d23d
counted in tree_bytes also the report's lists, a vertex array and a second
node array (bunny, sah-packet: 122 bytes a triangle then, 76 after): run
this on one reproduction's records (make_all refuses records of mixed
source trees). Per preset, over the
scenes with a record of it: the median, lowest and highest tree_bytes /
N_tri, and the median of N_TP / N_tri. Beside them, Embree's BVH on the same
scenes (the embree.bvh_bytes of the sah-packet records that have it: what
Embree's build leaves allocated, by its memory monitor), the median and range
of its bytes per triangle and of ours over its, scene by scene.

Output: the macros (TreeBytes*) of the report's paragraph on memory, and
tree_memory.tex: per scene, the sah-packet tree's references and bytes per
triangle beside Embree's BVH's bytes where the record has them.
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

FAST = "sah-packet"
BINNED = "sah-packet-binned"
REPORT = "clipping-pruning"
TARGET = 64  # bytes a triangle (issue 23)

MACROS = ["TreeBytesTarget", "TreeBytesFastScenes", "TreeBytesFastMedian", "TreeBytesFastMin",
          "TreeBytesFastMax", "TreeBytesFastAtMostTarget", "TreeRefsFastMedian",
          "TreeBytesBinnedMedian", "TreeBytesReportMedian", "TreeBytesEmbreeScenes",
          "TreeBytesEmbreeMedian", "TreeBytesEmbreeMin", "TreeBytesEmbreeMax",
          "TreeBytesOverEmbreeMedian", "TreeBytesOverEmbreeMin", "TreeBytesOverEmbreeMax"]


def _number(r, column):
    """A record's column (a dict or a frame's row) as a float, or None when
    it has none."""
    v = r[column] if column in r else None
    return float(v) if kr.present(v) else None


def _per_triangle(r, v):
    """v / the record's n_tri, or None without either."""
    if v is not None and kr.present(r["n_tri"]) and r["n_tri"]:
        return v / float(r["n_tri"])
    return None


def record_per_triangle(r, column):
    """A record's column / n_tri, or None without either."""
    return _per_triangle(r, _number(r, column))


def best_mode_bytes(r):
    """The bytes our best mode (kd_bvh_packet) reads, from a render_bench
    record (a dict or a frame's row): the BVH over the tree's leaves, its
    nodes and its own leaf packets (bvh_bytes + bvh_packet_bytes, records
    since session 47), or before those its nodes and the tree's nodes and
    leaf packets (bvh_bytes + tree_bytes); None without the BVH's bytes
    (records before 2026-12-07) or without either of the others. The one
    rule: analysis/embree_structure.py and experiments/bench_structure.py
    both take it (before 32f81fd each had its own copy)."""
    bvh, own, tree = (_number(r, c) for c in ("bvh_bytes", "bvh_packet_bytes", "tree_bytes"))
    if bvh is None:
        return None
    if own is not None:
        return bvh + own
    return bvh + tree if tree is not None else None


def best_mode_bytes_per_triangle(r):
    """best_mode_bytes / n_tri, or None without either."""
    return _per_triangle(r, best_mode_bytes(r))


def per_triangle(df, preset, column):
    """{scene: column / n_tri} over the scenes with a record of `preset`."""
    out = {}
    for scene in kr.scenes_in_order(df):
        if (scene, preset) not in df.index:
            continue
        v = record_per_triangle(df.loc[(scene, preset)], column)
        if v is not None:
            out[scene] = v
    return out


def over_embree(ours, embree):
    """{scene: our bytes over Embree's} where both are known."""
    return {s: ours[s] / embree[s] for s in embree if s in ours and embree[s] > 0}


def macros(df):
    def fmt(values, pick):
        return ("%.0f" % pick(values) if values else latex.DASH, True)

    ours = per_triangle(df, FAST, "tree_bytes")
    embree_by_scene = per_triangle(df, FAST, "embree_bvh_bytes")
    fast = list(ours.values())
    refs = list(per_triangle(df, FAST, "N_TP").values())
    binned = list(per_triangle(df, BINNED, "tree_bytes").values())
    report = list(per_triangle(df, REPORT, "tree_bytes").values())
    over = list(over_embree(ours, embree_by_scene).values())
    embree = list(embree_by_scene.values())

    def ratio(values, pick):
        return ("%.1f" % pick(values) if values else latex.DASH, True)

    return {
        "TreeBytesTarget": (str(TARGET), False),
        "TreeBytesFastScenes": (str(len(fast)), False),
        "TreeBytesFastMedian": fmt(fast, statistics.median),
        "TreeBytesFastMin": fmt(fast, min),
        "TreeBytesFastMax": fmt(fast, max),
        "TreeBytesFastAtMostTarget": (str(sum(b <= TARGET for b in fast)), False),
        "TreeRefsFastMedian": ("%.2f" % statistics.median(refs) if refs else latex.DASH, True),
        "TreeBytesBinnedMedian": fmt(binned, statistics.median),
        "TreeBytesReportMedian": fmt(report, statistics.median),
        "TreeBytesEmbreeScenes": (str(len(embree)), False),
        "TreeBytesEmbreeMedian": fmt(embree, statistics.median),
        "TreeBytesEmbreeMin": fmt(embree, min),
        "TreeBytesEmbreeMax": fmt(embree, max),
        "TreeBytesOverEmbreeMedian": ratio(over, statistics.median),
        "TreeBytesOverEmbreeMin": ratio(over, min),
        "TreeBytesOverEmbreeMax": ratio(over, max),
    }


def table(df):
    """tree_memory.tex: one row per scene with a sah-packet record."""
    ours = per_triangle(df, FAST, "tree_bytes")
    refs = per_triangle(df, FAST, "N_TP")
    embree = per_triangle(df, FAST, "embree_bvh_bytes")

    def cell(value, form):
        return form % value if value is not None else latex.DASH

    over = over_embree(ours, embree)
    body = []
    for scene, bytes_ in ours.items():
        n_tri = df.loc[(scene, FAST)]["n_tri"]
        body.append([latex.escape(scene), latex.fmt_int(int(n_tri)), cell(refs.get(scene), "%.2f"),
                     "%.0f" % bytes_, cell(embree.get(scene), "%.0f"),
                     cell(over.get(scene), "%.2f")])
    if not body:
        body = [["\\emph{no records of sah-packet}", "", "", "", "", ""]]
    header = ["Scene", "$N_{tri}$", "$N_{TP}/N_{tri}$", "ours", "Embree", "ours / Embree"]
    caption = ("Memory of the acceleration structures, in bytes per triangle: our tree "
               "\\texttt{sah-packet} (its 8-byte nodes and its leaf packets, a triangle "
               "stored once per reference, $N_{TP}$ references in all) and Embree~3's BVH "
               "(MEDIUM build), what \\texttt{rtcCommitScene} leaves allocated by "
               "Embree's memory monitor. Neither counts the triangle soup itself. A "
               "dash: the record has no Embree bytes (kdrt before 2026-12-06, or without "
               "Embree).")
    return latex.booktabs(header, body, align="lrrrrr", caption=caption,
                          label="tab:tree-memory", size="footnotesize",
                          groups=[("", 3), ("bytes per triangle", 3)])


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the tree memory", timings=False)
    ctx.write("tree_memory.tex", table(df))
    return macros(df)
