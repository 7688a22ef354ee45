"""Embree 3 on the identical rays, single thread: per scene, the kd-tree
variant that renders fastest and the report's final variant (clipping and
pruning) against Embree's build and render, with the rays on which the two
disagree, classed as kdrt's comparison (cc/render/compare.h) classes them in
exact arithmetic: grazing (the ray passes within 4 ulps of an edge), at the
origin (the origin within 8 ulps of the plane of a reported triangle), other
(including a hit below the watertight t bound); and which tracer was wrong.

Embree runs in the same kdrt process as each kd-tree run, on its rays, so a
scene has one Embree run per variant. Its times are the median of those runs:
on a loaded machine a single run's time varies (in the full profile's first
run Embree's T_R on one scene ranged from 0.17 to 0.44 s over the nine), and
dividing by the Embree run that happened to sit beside the fastest kd-tree run
favoured whichever run Embree was slow in.

Output: embree.tex and macros (median and range of the perf ratio).
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex

FINAL = "clipping-pruning"
BEYOND = "sah-packet"  # our fastest trees (kdtree_results.BEYOND)


def _sum(recs, col):
    total = 0
    for _, r in recs:
        v = r[col] if col in r else None
        if kr.present(v):
            total += int(v)
    return total


def embree_medians(df, scene):
    """Embree's T_B and T_R on a scene: the medians of its runs beside every
    kd-tree run (the nine and the variants beyond them), and their count;
    (None, None, 0) without one."""
    runs = []
    for v in kr.VARIANTS + kr.BEYOND:
        if (scene, v) in df.index:
            r = df.loc[(scene, v)]
            if kr.present(r["embree_T_R"]):
                runs.append(r)
    if not runs:
        return None, None, 0
    t_b = [float(r["embree_T_B"]) for r in runs if kr.present(r["embree_T_B"])]
    return (statistics.median(t_b) if t_b else None,
            statistics.median(float(r["embree_T_R"]) for r in runs), len(runs))


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        recs = [(v, df.loc[(scene, v)]) for v in kr.VARIANTS
                if (scene, v) in df.index]
        recs = [(v, r) for v, r in recs if kr.present(r["embree_T_R"])]
        if not recs:
            continue
        best_v, best = min(recs, key=lambda vr: vr[1]["T_R"])
        final = dict(recs).get(FINAL)
        beyond = None
        if (scene, BEYOND) in df.index:
            b = df.loc[(scene, BEYOND)]
            if kr.present(b["embree_T_R"]):
                beyond = b
        # Embree ran beside every kd-tree run of the scene; its times are the
        # medians of those runs (see the module doc).
        emb_t_b, emb_t_r, n_runs = embree_medians(df, scene)
        out.append({
            "scene": scene, "n_tri": best["n_tri"], "best_variant": best_v,
            "best_T_R": best["T_R"], "best_T_B": best["T_B"],
            "final_T_R": None if final is None else final["T_R"],
            "embree_T_B": emb_t_b, "embree_T_R": emb_t_r,
            "embree_runs": n_runs,
            "ratio_best": emb_t_r / best["T_R"],
            "ratio_final": None if final is None else emb_t_r / final["T_R"],
            "beyond_T_B": None if beyond is None else beyond["T_B"],
            "beyond_T_R": None if beyond is None else beyond["T_R"],
            "ratio_beyond": None if beyond is None else emb_t_r / beyond["T_R"],
            "ratio_fast": (emb_t_r / beyond["T_R_fast"]
                           if beyond is not None and kr.present(beyond["T_R_fast"])
                           else None),
            "grazing": _sum(recs, "embree_grazing"),
            "at_origin": _sum(recs, "embree_at_origin"),
            "other": _sum(recs, "embree_other") + _sum(recs, "embree_t_guard"),
            "kd_wrong": _sum(recs, "kd_wrong"),
            "embree_wrong": _sum(recs, "embree_wrong"),
            "runs": len(recs),
        })
    return out


def render(data):
    header = ["Scene", "$N_{tri}$", "Fastest kd variant", "$T_B$ kd",
              "$T_B$ Embree", "$T_R$ kd", "$T_R$ Embree", "perf kd/Embree",
              "$T_R$ clip+prune", "clip+prune/Embree", "$T_B$ SAH-4",
              "$T_R$ SAH-4", "SAH-4/Embree", "fast/Embree", "Grazing",
              "At origin", "Other", "kd wrong", "Embree wrong"]
    body = []
    for r in data:
        body.append([
            latex.escape(r["scene"]), latex.fmt_int(int(r["n_tri"])),
            latex.escape(kr.TITLES[r["best_variant"]]),
            latex.fmt_float(r["best_T_B"], 3),
            latex.fmt_float(r["embree_T_B"], 3) if r["embree_T_B"] else latex.DASH,
            latex.fmt_float(r["best_T_R"], 3), latex.fmt_float(r["embree_T_R"], 3),
            "%.2f" % r["ratio_best"],
            latex.fmt_float(r["final_T_R"], 3) if r["final_T_R"] else latex.DASH,
            "%.2f" % r["ratio_final"] if r["ratio_final"] else latex.DASH,
            latex.fmt_float(r["beyond_T_B"], 3) if r["beyond_T_B"] else latex.DASH,
            latex.fmt_float(r["beyond_T_R"], 3) if r["beyond_T_R"] else latex.DASH,
            "%.2f" % r["ratio_beyond"] if r["ratio_beyond"] else latex.DASH,
            "%.2f" % r["ratio_fast"] if r["ratio_fast"] else latex.DASH,
            latex.fmt_int(r["grazing"]), latex.fmt_int(r["at_origin"]),
            latex.fmt_int(r["other"]), latex.fmt_int(r["kd_wrong"]),
            latex.fmt_int(r["embree_wrong"])])
    if not body:
        body = [["\\emph{no Embree runs}"] + [""] * (len(header) - 1)]
    caption = ("Embree 3 (MEDIUM quality build, one thread, "
               "\\texttt{rtcIntersect1}/\\texttt{rtcOccluded1}) on the same rays "
               "as our kd-tree. Embree's times are the medians of its runs on "
               "the scene, one beside each kd-tree run. perf kd/Embree is "
               "Embree's render time over ours (1 = as fast as Embree). SAH-4 is our tree beyond the "
               "report (preset \\texttt{sah-packet}: the full SAH counted per "
               "packet of 4, $K_T = 45$, hybrid split search, clipping and pruning); "
               "fast/Embree is Embree's render time over that tree's in our renderer's "
               "fastest mode (primary and shadow rays in packets of $2\\times 2$ pixels, "
               "shadow rays leaving their origin triangle untested; the same image). "
               "Disagreements are summed over "
               "the nine variants and judged in exact arithmetic: "
               "``grazing'' rays pass within 4 ulps of a triangle edge "
               "(measured across the ray), ``at origin'' rays start within 8 "
               "ulps of the plane of a triangle one tracer reports, so the "
               "sign of $t$ is within rounding; ``other'' would be real "
               "errors. The last two columns count the rays on which exact "
               "arithmetic says the kd-tree, or Embree, is the one that is "
               "wrong.")
    return latex.booktabs(header, body, align="lrlrrrrrrrrrrrrrrrr", caption=caption,
                          label="tab:embree", size="scriptsize")


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    data = rows(df)
    ctx.write("embree.tex", render(data))
    ratios = [r["ratio_best"] for r in data]

    def ratio_macros(prefix, key):
        """Median, range and count of a ratio column over the scenes that have
        it, and how many of those of 50,000 triangles or more reach 0.7."""
        values = [r[key] for r in data if r[key] is not None]
        big = [r[key] for r in data if r[key] is not None and r["n_tri"] >= 50000]

        def stat(f):
            return ("%.2f" % f(values) if values else latex.DASH, True)

        return {
            prefix + "Scenes": (str(len(values)), False),
            prefix + "RatioMedian": stat(statistics.median),
            prefix + "RatioMin": stat(min),
            prefix + "RatioMax": stat(max),
            prefix + "BigScenes": (str(len(big)), False),
            prefix + "BigAtLeastSeventy": (str(sum(x >= 0.7 for x in big)), False),
        }

    return {
        **ratio_macros("EmbreePacket", "ratio_beyond"),
        **ratio_macros("EmbreeFast", "ratio_fast"),
        "EmbreeScenes": (str(len(data)), False),
        "EmbreeRatioMedian": ("%.2f" % statistics.median(ratios) if ratios
                              else latex.DASH, True),
        "EmbreeRatioMin": ("%.2f" % min(ratios) if ratios else latex.DASH, True),
        "EmbreeRatioMax": ("%.2f" % max(ratios) if ratios else latex.DASH, True),
        "EmbreeOtherDisagreements": (latex.fmt_int(sum(r["other"] for r in data)),
                                     False),
        "EmbreeGrazingDisagreements": (latex.fmt_int(
            sum(r["grazing"] for r in data)), False),
        "EmbreeAtOriginDisagreements": (latex.fmt_int(
            sum(r["at_origin"] for r in data)), False),
        "EmbreeKdWrong": (latex.fmt_int(sum(r["kd_wrong"] for r in data)), False),
        "EmbreeEmbreeWrong": (latex.fmt_int(
            sum(r["embree_wrong"] for r in data)), False),
    }
