"""The Embree comparison's three tables (analysis/embree.py builds their
rows): tab:embree (times and paired ratios per scene), tab:embree-rays (the
rays on which the kd-tree and Embree disagree, judged in exact arithmetic)
and tab:embree-robust (against Embree built with RTC_SCENE_FLAG_ROBUST).
"""

from analysis import kdtree_results as kr
from analysis import latex


def _time(v):
    return latex.fmt_float(v, 3) if kr.present(v) and v else latex.DASH


def _ratio(v):
    return "%.2f" % v if v is not None else latex.DASH


def render(data):
    """The times and paired ratios per scene (tab:embree)."""
    groups = [("", 2), ("Fastest of the nine", 3), ("Embree", 2),
              ("Clipping pruning", 2), ("SAH-4", 4)]
    header = ["Scene", "$N_{tri}$", "variant", "$T_B$", "$T_R$", "$T_B$", "$T_R$",
              "$T_R$", "/Embree", "$T_B$", "$T_R$", "/Embree", "fast/Embree"]
    body = []
    for r in data:
        body.append([
            latex.escape(r["scene"]), latex.fmt_int(int(r["n_tri"])),
            latex.escape(kr.TITLES[r["best_variant"]]),
            _time(r["best_T_B"]), _time(r["best_T_R"]),
            _time(r["embree_T_B"]), _time(r["embree_T_R"]),
            _time(r["final_T_R"]), _ratio(r["ratio_final"]),
            _time(r["beyond_T_B"]), _time(r["beyond_T_R"]),
            _ratio(r["ratio_beyond"]), _ratio(r["ratio_fast"])])
    if not body:
        body = [["\\emph{no Embree runs}"] + [""] * (len(header) - 1)]
    unpaired = sum(r["unpaired"] for r in data)
    caption = ("Embree 3 (MEDIUM quality build, one thread, "
               "\\texttt{rtcIntersect1}/\\texttt{rtcOccluded1}) on the same rays "
               "as our kd-tree, in the same process, the two tracers' timed "
               "rounds alternating, beside the report's final variant (clipping "
               "and pruning) and our trees beyond the report; beside the other "
               "variants Embree is built once, untimed, to compare every ray "
               "(Table~\\ref{tab:embree-rays}). "
               "Times are medians of the timed rounds "
               "(Embree's over every timed run of the scene); the fastest of "
               "the nine is by its own $T_R$. The ratios (/Embree) are paired: the median "
               "over the rounds of a "
               "run of Embree's render time over ours in the same round (1 = "
               "as fast as Embree; Figure~\\ref{fig:embree-ratio} shows the "
               "spread of the final variant's and the fast mode's). SAH-4 is "
               "our tree beyond the report (preset \\texttt{sah-packet}: the full SAH counted per "
               "packet of 4, $K_T = 45$, hybrid split search, clipping and pruning), "
               "its /Embree with single rays under the report's rules (the "
               "figure's circles are the fastest of its three single-ray modes); "
               "fast/Embree is the paired ratio of that tree in our renderer's "
               "fastest mode (primary and shadow rays in packets of $4\\times 4$ pixels, "
               "shadow rays leaving their origin triangle untested and searched from "
               "the light; the same image).%s" % (
                   " %d run%s recorded no paired ratio (made before kdrt paired "
                   "its rounds) and give%s none." % (
                       unpaired, "" if unpaired == 1 else "s",
                       "s" if unpaired == 1 else "") if unpaired else ""))
    return latex.booktabs(header, body, align="lrlrrrrrrrrrr", caption=caption,
                          label="tab:embree", size="footnotesize", groups=groups)


def render_rays(data):
    """The rays on which the kd-tree and Embree disagree (tab:embree-rays)."""
    header = ["Scene", "Grazing", "At origin", "Other", "kd wrong", "Embree wrong"]
    body = [[latex.escape(r["scene"]), latex.fmt_int(r["grazing"]),
             latex.fmt_int(r["at_origin"]), latex.fmt_int(r["other"]),
             latex.fmt_int(r["kd_wrong"]), latex.fmt_int(r["embree_wrong"])] for r in data]
    if not body:
        body = [["\\emph{no Embree runs}"] + [""] * (len(header) - 1)]
    caption = ("The rays on which our kd-tree and Embree 3 disagree (hit or "
               "miss, or $t$ by more than $10^{-4}$ relative), summed over every "
               "variant and judged in exact arithmetic: "
               "``grazing'' rays pass within 4 ulps of a triangle edge "
               "(measured across the ray), ``at origin'' rays start within 8 "
               "ulps of the plane of a triangle one tracer reports, so the "
               "sign of $t$ is within rounding; ``other'' would be real "
               "errors. The last two columns count the rays on which exact "
               "arithmetic says the kd-tree, or Embree, is the one that is "
               "wrong.")
    return latex.booktabs(header, body, align="lrrrrr", caption=caption,
                          label="tab:embree-rays", size="footnotesize")


def render_robust(data):
    """Our tree sah-packet against Embree at its default flags and built
    with RTC_SCENE_FLAG_ROBUST, timed in the same rounds (tab:embree-robust):
    single rays against single rays, best mode against best mode, and the
    rays exact arithmetic proves the robust Embree wrong on."""
    groups = [("", 2), ("Single rays", 2), ("Best mode", 2), ("Robust Embree wrong", 2)]
    header = ["Scene", "$N_{tri}$", "/Embree", "/robust", "/Embree", "/robust",
              "primary", "shadow"]
    body = [[latex.escape(r["scene"]), latex.fmt_int(int(r["n_tri"])),
             _ratio(r["ratio_single"]), _ratio(r["ratio_robust_single"]),
             _ratio(r["ratio_best"]), _ratio(r["ratio_robust_best"]),
             latex.fmt_int(r["robust_wrong"][0]), latex.fmt_int(r["robust_wrong"][1])]
            for r in data if r["ratio_robust_single"] is not None]
    if not body:
        body = [["\\emph{no runs with Embree's robust setting}"] + [""] * (len(header) - 1)]
    caption = ("Our tree \\texttt{sah-packet} against Embree~3 at its default "
               "flags (/Embree) and against the same "
               "Embree built with \\texttt{RTC\\_SCENE\\_FLAG\\_ROBUST} (/robust: "
               "``robust traversal'', no ``optimizations that reduce arithmetic "
               "accuracy''), both timed in the same rounds and paired per round: "
               "Embree's render time over ours. Single rays: Embree's single "
               "rays over the fastest of our three single-ray modes (the report's "
               "rules; shadow rays leaving their origin triangle untested and "
               "searched from the light, one ray at a time; those rays through "
               "a BVH over the tree's leaves); best mode: per "
               "round the faster of each side's single rays and packets. Our "
               "watertight test answers every ray exactly; the last two "
               "columns count the rays on which exact arithmetic proves the "
               "robust Embree wrong (its default flags' wrong rays are in "
               "Table~\\ref{tab:embree-rays}).")
    return latex.booktabs(header, body, align="lrrrrrrr", caption=caption,
                          label="tab:embree-robust", size="footnotesize", groups=groups)
