"""Build time against Embree: our fast binned tree beside the report's.

Per scene with a run of sah-packet-binned (the full SAH counted per packet of
four, 16 bins on the driving axis, no clipping: cc/kdtree/config.h), its
build and render times beside the report's fastest-building binned variant
(binning-8-driving) and Embree 3's MEDIUM build on the same rays, one thread.
Embree's times shown are the medians of all its timed rounds on the scene
(embree.embree_medians, as in Table tab:embree). The binned tree's ratios to
Embree are paired per round within its own run: render, the record's
embree.paired_ratio; build, the median over the rounds of Embree's T_B over
ours in the same round (both *_runs lists hold the same rounds; a run whose
lists differ in length gives no build ratio). A run without paired rounds
gives no ratio to Embree.

Output: embree_build.tex and macros (medians of the ratios, and the number
of scenes where the binned tree both builds and renders faster than the
report's binning-8-driving).
"""

import statistics

from analysis import embree
from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

FAST = "sah-packet-binned"
REPORT = "binning-8-driving"


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        if (scene, FAST) not in df.index:
            continue
        fast = df.loc[(scene, FAST)]
        if not (kr.present(fast["T_B"]) and kr.present(fast["T_R"])):
            continue
        report = df.loc[(scene, REPORT)] if (scene, REPORT) in df.index else None
        emb_t_b, emb_t_r, _ = embree.embree_medians(df, scene)
        row = {"scene": scene, "n_tri": fast["n_tri"],
               "T_B": float(fast["T_B"]), "T_R": float(fast["T_R"]),
               "report_T_B": None, "report_T_R": None,
               "embree_T_B": emb_t_b, "embree_T_R": emb_t_r,
               "build_ratio": paired_build(fast),
               "perf_ratio": embree.paired(fast, "embree_ratio")[0]}
        if report is not None and kr.present(report["T_B"]) and kr.present(report["T_R"]):
            row["report_T_B"] = float(report["T_B"])
            row["report_T_R"] = float(report["T_R"])
        out.append(row)
    return out


def paired_build(r):
    """Median over the rounds of Embree's T_B over the tree's in the same
    round; None unless the run recorded rounds of both and as many."""
    ours, theirs = r["T_B_runs"], r["embree_T_B_runs"]
    if not kr.present(r["embree_ratio"]) or not isinstance(ours, list) \
            or not isinstance(theirs, list) or len(ours) != len(theirs) \
            or not ours or not all(ours):
        return None
    return statistics.median(e / k for e, k in zip(theirs, ours))


def _ratio(a, b):
    """a / b, or None when either is missing or b is 0."""
    if a is None or b is None or not b:
        return None
    return a / b


def render(data):
    groups = [("", 2), ("Build $T_B$ (s)", 3), ("", 1), ("Render $T_R$ (s)", 3), ("", 1),
              ("binned/B8D", 2)]
    header = ["Scene", "$N_{tri}$", "Embree", "B8D", "binned", "build Embree/binned",
              "Embree", "B8D", "binned", "perf binned/Embree", "build", "perf"]

    def cell(v, digits=3):
        return latex.fmt_float(v, digits) if v is not None else latex.DASH

    def ratio(v):
        return "%.2f" % v if v is not None else latex.DASH

    body = []
    for r in data:
        body.append([
            latex.escape(r["scene"]), latex.fmt_int(int(r["n_tri"])),
            cell(r["embree_T_B"]), cell(r["report_T_B"]), cell(r["T_B"]),
            ratio(r["build_ratio"]),
            cell(r["embree_T_R"]), cell(r["report_T_R"]), cell(r["T_R"]),
            ratio(r["perf_ratio"]),
            ratio(_ratio(r["report_T_B"], r["T_B"])),
            ratio(_ratio(r["report_T_R"], r["T_R"]))])
    if not body:
        body = [["\\emph{no runs of sah-packet-binned}"] + [""] * (len(header) - 1)]
    caption = ("Build and render time of our fast binned tree (preset "
               "\\texttt{sah-packet-binned}: the full SAH counted per packet of "
               "4, $K_T = 45$, 16 bins on the driving axis, no clipping), of the "
               "report's fastest-building binned variant (B8D: binning 8, "
               "driving axis) and of Embree 3 (MEDIUM build), one thread, on the "
               "same rays. $T_B$ is mesh in memory to traversable tree; times are "
               "medians of the timed rounds (Embree's over every run of the "
               "scene); ``binned'' is SAH-4 binned. Ratios above 1 favour the binned tree: build "
               "Embree/binned is Embree's build time over ours and perf "
               "binned/Embree Embree's render time over ours, each the median "
               "over the rounds of one run in which the two alternated; "
               "binned/B8D divides the report variant's time by ours.")
    return latex.booktabs(header, body, align="lrrrrrrrrrrr", caption=caption,
                          label="tab:embree-build", size="footnotesize", groups=groups)


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the binned-build table")
    data = rows(df)
    ctx.write("embree_build.tex", render(data))

    def med(values):
        values = [v for v in values if v is not None]
        return ("%.2f" % statistics.median(values) if values else latex.DASH, True)

    build_emb = [r["build_ratio"] for r in data]
    perf_emb = [r["perf_ratio"] for r in data]
    build_rep = [_ratio(r["report_T_B"], r["T_B"]) for r in data]
    perf_rep = [_ratio(r["report_T_R"], r["T_R"]) for r in data]
    both = sum(1 for b, p in zip(build_rep, perf_rep)
               if b is not None and p is not None and b > 1 and p > 1)
    compared = sum(1 for b, p in zip(build_rep, perf_rep) if b is not None and p is not None)
    return {
        "BinnedScenes": (str(len(data)), False),
        "BinnedBuildOverEmbreeMedian": med(build_emb),
        "BinnedPerfOverEmbreeMedian": med(perf_emb),
        "BinnedBuildOverReportMedian": med(build_rep),
        "BinnedPerfOverReportMedian": med(perf_rep),
        "BinnedBeatsReportBoth": (str(both), False),
        "BinnedComparedWithReport": (str(compared), False),
    }
