"""Embree 3 on the identical rays, single thread: per scene, the kd-tree
variant that renders fastest and the report's final variant (clipping and
pruning) against Embree's build and render, with the rays on which the two
disagree (grazing a silhouette edge within float rounding, and other).

Output: embree.tex and macros (median and range of the perf ratio).
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex

FINAL = "clipping-pruning"


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        recs = [(v, df.loc[(scene, v)]) for v in kr.VARIANTS
                if (scene, v) in df.index]
        recs = [(v, r) for v, r in recs
                if r["embree_T_R"] is not None and r["embree_T_R"] == r["embree_T_R"]]
        if not recs:
            continue
        best_v, best = min(recs, key=lambda vr: vr[1]["T_R"])
        final = dict(recs).get(FINAL)
        out.append({
            "scene": scene, "n_tri": best["n_tri"], "best_variant": best_v,
            "best_T_R": best["T_R"], "best_T_B": best["T_B"],
            "final_T_R": None if final is None else final["T_R"],
            "embree_T_B": best["embree_T_B"], "embree_T_R": best["embree_T_R"],
            "ratio_best": best["embree_T_R"] / best["T_R"],
            "ratio_final": (None if final is None
                            else final["embree_T_R"] / final["T_R"]),
            "grazing": sum(int(r["embree_grazing"] or 0) for _, r in recs),
            "other": sum(int(r["embree_other"] or 0) for _, r in recs),
            "runs": len(recs),
        })
    return out


def render(data):
    header = ["Scene", "$N_{tri}$", "Fastest kd variant", "$T_B$ kd",
              "$T_B$ Embree", "$T_R$ kd", "$T_R$ Embree", "perf kd/Embree",
              "$T_R$ clip+prune", "clip+prune/Embree", "Grazing", "Other"]
    body = []
    for r in data:
        body.append([
            latex.escape(r["scene"]), latex.fmt_int(int(r["n_tri"])),
            latex.escape(kr.TITLES[r["best_variant"]]),
            latex.fmt_float(r["best_T_B"], 3), latex.fmt_float(r["embree_T_B"], 3),
            latex.fmt_float(r["best_T_R"], 3), latex.fmt_float(r["embree_T_R"], 3),
            "%.2f" % r["ratio_best"],
            latex.fmt_float(r["final_T_R"], 3) if r["final_T_R"] else latex.DASH,
            "%.2f" % r["ratio_final"] if r["ratio_final"] else latex.DASH,
            latex.fmt_int(r["grazing"]), latex.fmt_int(r["other"])])
    if not body:
        body = [["\\emph{no Embree runs}"] + [""] * (len(header) - 1)]
    caption = ("Embree 3 (MEDIUM quality build, one thread, "
               "\\texttt{rtcIntersect1}/\\texttt{rtcOccluded1}) on the same rays "
               "as our kd-tree. perf kd/Embree is Embree's render time over "
               "ours (1 = as fast as Embree). Disagreements are summed over "
               "the nine variants: ``grazing'' rays hit within $10^{-5}$ "
               "(barycentric) of an edge, where float rounding decides; "
               "``other'' would be real errors.")
    return latex.booktabs(header, body, align="lrlrrrrrrrrr", caption=caption,
                          label="tab:embree", size="scriptsize")


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    data = rows(df)
    ctx.write("embree.tex", render(data))
    ratios = [r["ratio_best"] for r in data]
    return {
        "EmbreeScenes": (str(len(data)), False),
        "EmbreeRatioMedian": ("%.2f" % statistics.median(ratios) if ratios
                              else latex.DASH, True),
        "EmbreeRatioMin": ("%.2f" % min(ratios) if ratios else latex.DASH, True),
        "EmbreeRatioMax": ("%.2f" % max(ratios) if ratios else latex.DASH, True),
        "EmbreeOtherDisagreements": (latex.fmt_int(sum(r["other"] for r in data)),
                                     False),
        "EmbreeGrazingDisagreements": (latex.fmt_int(
            sum(r["grazing"] for r in data)), False),
    }
