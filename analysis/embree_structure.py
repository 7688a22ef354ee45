"""What the kd-tree's structure costs against Embree (issue 23): our tree
sah-packet beside a baseline that has Embree's kind of structure and our
kernels.

The baseline (kdrt --triangle_bvh, matrix.json's triangle_bvh_variants;
cc/kdtree/triangle_bvh.h) is a BVH of whole triangles, each in one leaf
(binned SAH over the centroids, eight-wide nodes), traced by the very kernels
that trace the BVH over the kd-tree's leaves: the same box test, the same
exact leaf test, the same answers. It is not a kd-tree and not one of our
modes. kdrt times it in the same rounds as the kd-tree and Embree, on the
fast mode's rays, one at a time and in its 4x4 packets, and pairs it with
Embree per round as it pairs our tree (record fast_render.triangle_bvh). So
on a scene, what the baseline gains over our tree is what the kd-tree's
structure costs (its leaves hold a fragment of every triangle that crosses
their cells), and what it still lacks against Embree is the kernels'.

Per scene with a run that timed the baseline: best mode against Embree's
best mode (the paired median with the rounds' range) and single rays against
Embree's single rays (the paired median), our tree's and the baseline's; and
the bytes a
triangle of our tree, the baseline and Embree's BVH. Runs made before kdrt
timed the baseline are left out.

Output: embree_structure.tex and macros (EmbreeTri*: medians, ranges and
counts over those scenes, our tree's best mode over the same scenes, and the
baseline's bytes a triangle).
"""

import statistics

from analysis import embree
from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance
from analysis import tree_memory

TREE = embree.BEYOND  # sah-packet: the tree the baseline is timed beside
MACROS = [p + s for p in ("EmbreeTriBest", "EmbreeTriSingle", "EmbreeTriKdBest")
          for s in ("Scenes", "RatioMedian", "RatioMin", "RatioMax", "BigScenes",
                    "BigAtLeastSeventy", "BigAtLeastEighty", "BigAtLeastOne")] + \
    ["EmbreeTriBytes" + s for s in ("Min", "Max", "Median")] + ["EmbreeTriClause"]
# A median quotient within this of 1 is read as no difference: two copies
# of the same structure, paired in one process, gave 0.98-1.02 per scene
# (render_bench, 5 rounds, six scenes; 2026-12-07).
NOISE = 0.02


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        if (scene, TREE) not in df.index:
            continue
        r = df.loc[(scene, TREE)]
        tri = embree.ratio_cell(r, "tri_best_ratio")
        if tri is None:
            continue
        out.append({"scene": scene, "n_tri": int(r["n_tri"]),
                    "kd_best": embree.ratio_cell(r, "best_ratio"), "tri_best": tri,
                    "kd_single": embree.ratio_cell(r, "single_ratio"),
                    "tri_single": embree.ratio_cell(r, "tri_single_ratio"),
                    "kd_bytes": tree_memory.best_mode_bytes_per_triangle(r),
                    "tri_bytes": tree_memory.record_per_triangle(r, "tri_bytes"),
                    "embree_bytes": tree_memory.record_per_triangle(r, "embree_bvh_bytes")})
    return out


def _median(cell):
    return "%.2f" % cell[0] if cell is not None else latex.DASH


def _bytes(v):
    return "%.0f" % v if v is not None else latex.DASH


def render(data):
    groups = [("", 2), ("Best mode", 2), ("Single rays", 2), ("Bytes a triangle", 3)]
    header = ["Scene", "$N_{tri}$", "kd-tree", "baseline", "kd-tree", "baseline",
              "kd-tree", "baseline", "Embree"]
    body = [[latex.escape(r["scene"]), latex.fmt_int(r["n_tri"]),
             embree.fmt_cell(r["kd_best"]), embree.fmt_cell(r["tri_best"]),
             _median(r["kd_single"]), _median(r["tri_single"]),
             _bytes(r["kd_bytes"]), _bytes(r["tri_bytes"]), _bytes(r["embree_bytes"])]
            for r in data]
    if not body:
        body = [["\\emph{no runs with the baseline}"] + [""] * (len(header) - 1)]
    caption = ("What the kd-tree's structure costs: our tree \\texttt{sah-packet} "
               "and a baseline, a BVH of whole triangles (binned SAH, each "
               "triangle in one leaf of at most 16, eight-wide nodes; not a "
               "kd-tree) traced by the same kernels, with the same answers, both "
               "against Embree~3 (MEDIUM build, one thread) on the same rays in "
               "the same rounds. A ratio is the median over the rounds of "
               "Embree's render time over ours in the same round (above 1: ours "
               "is the faster), in best mode with the rounds' range. Best mode: per round the "
               "faster of Embree's single rays and its 16-ray packets over the "
               "fastest of our tree's five modes, or over the faster of the "
               "baseline's two (the fast mode's rays one at a time and in its "
               "$4\\times 4$ packets); single rays: Embree's over the fastest of "
               "our tree's three single-ray modes, or over the baseline's. Bytes: "
               "what the kd-tree's best mode reads, the nodes of the BVH over its "
               "leaves and their packets (the leaves' triangles regrouped; in "
               "runs before that, the tree's nodes and leaf packets and the BVH's "
               "nodes), the baseline's nodes and leaf packets, and what Embree's "
               "build left allocated.")
    return latex.booktabs(header, body, align="lrllllrrr", caption=caption,
                          label="tab:embree-structure", size="footnotesize", groups=groups)


def conclusion(data):
    """The report's sentence on what the baseline shows: per scene the
    baseline's best-mode ratio over our tree's (both paired with Embree in
    the same rounds), its median and range, and what that says."""
    q = [r["tri_best"][0] / r["kd_best"][0] for r in data
         if r["kd_best"] is not None and r["kd_best"][0]]
    if not q:
        return "No run timed the baseline beside our tree's best mode."
    m = statistics.median(q)
    head = ("Per scene, the baseline's best mode is %.2f times as fast as our tree's at the "
            "median (%.2f to %.2f over %d scenes)" % (m, min(q), max(q), len(q)))
    if m > 1 + NOISE:
        return head + (": most of what our best mode lacks is the kd-tree's structure (a kd "
                       "leaf holds a fragment of every triangle that crosses its cell, and a "
                       "packet that reaches it tests them all), and what the baseline still "
                       "lacks against Embree is the kernels'.")
    if m < 1 - NOISE:
        return head + ": the kd-tree's structure is not what holds our best mode back."
    return head + ": within the noise of the rounds, so the structure is not shown to cost."


def structure_macros(data):
    """EmbreeTriBest* and EmbreeTriSingle* (the baseline's ratios, as
    embree.ratio_macros gives them), EmbreeTriKdBest* (our tree's best mode
    over the same scenes) and the baseline's bytes a triangle."""
    flat = [{"n_tri": r["n_tri"],
             **{k: r[k][0] if r[k] is not None else None
                for k in ("kd_best", "tri_best", "kd_single", "tri_single")}} for r in data]
    sizes = [r["tri_bytes"] for r in data if r["tri_bytes"] is not None]
    return {
        **embree.ratio_macros(flat, "EmbreeTriBest", "tri_best"),
        **embree.ratio_macros(flat, "EmbreeTriSingle", "tri_single"),
        **embree.ratio_macros(flat, "EmbreeTriKdBest", "kd_best"),
        "EmbreeTriBytesMin": ("%.0f" % min(sizes) if sizes else latex.DASH, True),
        "EmbreeTriBytesMax": ("%.0f" % max(sizes) if sizes else latex.DASH, True),
        "EmbreeTriBytesMedian": ("%.0f" % statistics.median(sizes) if sizes else latex.DASH,
                                 True),
        "EmbreeTriClause": (conclusion(data), False),
    }


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the structure table")
    data = rows(df)
    ctx.write("embree_structure.tex", render(data))
    return structure_macros(data)
