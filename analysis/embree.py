"""Embree 3 on the identical rays, single thread: per scene, the report's
final variant (clipping and pruning) and our fastest tree (sah-packet, also
in the renderer's fastest mode) against Embree's build and render, the
fastest of the nine beside them, and the rays on which the two disagree
(over every variant), classed as kdrt's comparison (cc/render/compare.h)
classes them in exact arithmetic: grazing (the ray passes within 4 ulps of
an edge), at the origin (the origin within 8 ulps of the plane of a reported
triangle), other (including a hit below the watertight t bound); and which
tracer was wrong.

Embree runs in the same kdrt process as a kd-tree run, on its rays: on every
variant it is built once and compared ray by ray; on the variants of
experiments/matrix.json's embree_timed_variants its timed rounds alternate
with the kd-tree's (embree.timed; the others record no Embree times). The
kd/Embree ratio of a variant on a scene is that record's paired median: the
median over the rounds of Embree's T_R over the kd-tree's T_R in the same
round (embree.paired_ratio; for the fast mode fast_render.paired_ratio), so
the load of the machine during a round hits both tracers alike. Best mode
against best mode (#23's fair bar): with the fast mode, Embree's packet calls
(rtcIntersect16 / rtcOccluded16 on the same 4x4 blocks) are timed in the same
rounds, and per round the faster of Embree's two modes is divided by the
faster of ours (fast_render.best_paired_ratio; series "best"). Single rays
against single rays (#23's other bar; series "single", macros
EmbreeSingle*): per round Embree's single rays over the fastest of our
single-ray modes, the report's rules, the fast mode's shadow rays one ray
at a time, and those rays through the BVH over the tree's leaves
(fast_render.single_paired_ratio). Time to image
(macros EmbreeImage*): Embree's build plus its best render over our build
plus our best render, each the median of its rounds (time_to_image), for
the better per scene of our two trees IMAGE_TREES (sah-packet renders
fastest, sah-packet-binned builds fastest; the row names the one used). A
record
without paired ratios (made before they were recorded) gives no ratio: its
cells are dashes and the caption counts them. Embree's times shown are the
medians of all its timed rounds on the scene (over every kd-tree run that
timed it).

Embree's robust setting (kdrt --embree_robust): beside our fast mode a
second Embree, built with RTC_SCENE_FLAG_ROBUST, is timed in the same rounds
(single rays and packets); its ratios are paired like the others
(fast_render.embree_robust), and the rays exact arithmetic proves it wrong on
are counted by ray kind (embree_robust.tex, embree_robust_ratio.pdf, macros
EmbreeRobust*).

Output (the three tables set by embree_tables.py): embree.tex,
embree_rays.tex, embree_robust.tex, embree_ratio.pdf and
embree_robust_ratio.pdf (the paired ratios per scene with their
spread over the rounds) and macros (median
and range of the perf ratios; OursOverFinal* and OursFastOverFinal*: our
fastest tree, and its fast mode, over the report's final variant, as the
quotient of their paired ratios to Embree).
"""

import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import embree_tables  # noqa: E402
from analysis import figures  # noqa: E402
from analysis import kdtree_results as kr  # noqa: E402
from analysis import latex  # noqa: E402
from analysis import provenance  # noqa: E402

FINAL = "clipping-pruning"
BEYOND = "sah-packet"  # our fastest trees (kdtree_results.BEYOND)
# The trees time to image may use (both run in the fast mode with Embree
# timed, experiments/matrix.json): the fastest to render and the fastest to
# build of our SAH trees.
IMAGE_TREES = ("sah-packet", "sah-packet-binned")


def _sum(recs, col):
    total = 0
    for _, r in recs:
        v = r[col] if col in r else None
        if kr.present(v):
            total += int(v)
    return total


def _runs(r, runs_col, median_col):
    """A record's timed rounds of a column (its median alone when the record
    has no rounds)."""
    runs = r[runs_col]
    if isinstance(runs, list) and runs:
        return [float(x) for x in runs]
    return [float(r[median_col])] if kr.present(r[median_col]) else []


def embree_medians(df, scene):
    """Embree's T_B and T_R on a scene: the medians of all its timed rounds
    in every kd-tree run of the scene that ran it (the nine and the variants
    beyond them), and how many runs did; (None, None, 0) without one."""
    t_b, t_r, n = [], [], 0
    for v in kr.VARIANTS + kr.BEYOND:
        if (scene, v) in df.index and kr.present(df.loc[(scene, v)]["embree_T_R"]):
            r = df.loc[(scene, v)]
            n += 1
            t_b += _runs(r, "embree_T_B_runs", "embree_T_B")
            t_r += _runs(r, "embree_T_R_runs", "embree_T_R")
    if not n:
        return None, None, 0
    return (statistics.median(t_b) if t_b else None, statistics.median(t_r), n)


def paired(r, column):
    """(paired median, [ratio per round]) of a record's ratio column
    (embree_ratio or fast_ratio); (None, []) without one."""
    if r is None or not kr.present(r[column]):
        return None, []
    runs = r[column + "_runs"]
    return float(r[column]), [float(x) for x in runs] if isinstance(runs, list) else []


def ratio_cell(r, column):
    """(paired median, lowest, highest round) of a ratio column, or None
    without one (a record without its rounds gives its median thrice)."""
    median, runs = paired(r, column)
    if median is None:
        return None
    runs = runs or [median]
    return median, min(runs), max(runs)


def fmt_cell(cell):
    """A ratio_cell as the tables print it: the median, the range smaller."""
    if cell is None:
        return latex.DASH
    return "%.2f {\\scriptsize (%.2f--%.2f)}" % cell


def _with_embree(df, scene, variant):
    """The record of (scene, variant) when Embree was timed beside it."""
    r = _compared(df, scene, variant)
    return r if r is not None and kr.present(r["embree_T_R"]) else None


def _compared(df, scene, variant):
    """The record of (scene, variant) when Embree was run on its rays."""
    if (scene, variant) not in df.index:
        return None
    r = df.loc[(scene, variant)]
    return r if kr.present(r["embree_disagree"]) else None


def row(df, scene, recs):
    """One scene's row: the fastest of the nine by its own T_R (recs:
    [(variant, record)] of the runs compared with Embree, timed or not),
    clipping-pruning, sah-packet and its fast mode with their paired ratios
    and rounds, and the disagreements over every run in recs."""
    nine = [(v, r) for v, r in recs if v in kr.VARIANTS]
    best_v, best = min(nine or recs, key=lambda vr: vr[1]["T_R"])
    beyond = _with_embree(df, scene, BEYOND)
    final = _with_embree(df, scene, FINAL)
    emb_t_b, emb_t_r, n_runs = embree_medians(df, scene)
    out = {"scene": scene, "n_tri": best["n_tri"], "best_variant": best_v,
           "best_T_R": best["T_R"], "best_T_B": best["T_B"],
           "final_T_R": None if final is None else final["T_R"],
           "embree_T_B": emb_t_b, "embree_T_R": emb_t_r, "embree_runs": n_runs,
           "beyond_T_B": None if beyond is None else beyond["T_B"],
           "beyond_T_R": None if beyond is None else beyond["T_R"],
           "unpaired": sum(1 for r in (final, beyond)
                           if r is not None and not kr.present(r["embree_ratio"])),
           "grazing": _sum(recs, "embree_grazing"),
           "at_origin": _sum(recs, "embree_at_origin"),
           "other": _sum(recs, "embree_other") + _sum(recs, "embree_t_guard"),
           "kd_wrong": _sum(recs, "kd_wrong"),
           "embree_wrong": _sum(recs, "embree_wrong"), "runs": len(recs)}
    for key, r, column in (("final", final, "embree_ratio"),
                           ("beyond", beyond, "embree_ratio"),
                           ("single", beyond, "single_ratio"),
                           ("fast", beyond, "fast_ratio"),
                           ("best", beyond, "best_ratio"),
                           ("robust_single", beyond, "robust_single_ratio"),
                           ("robust_best", beyond, "robust_best_ratio"),
                           ("tri_single", beyond, "tri_single_ratio"),
                           ("tri_best", beyond, "tri_best_ratio")):
        out["ratio_" + key], out["runs_" + key] = paired(r, column)
    out["robust_wrong"] = (None if out["ratio_robust_single"] is None else
                           [int(beyond[c]) if kr.present(beyond[c]) else 0
                            for c in ("robust_wrong_primary", "robust_wrong_shadow")])
    # Its disagreements and those at a ray's origin; None in records from
    # before 2026-12-06, which did not keep the second.
    out["robust_disagree"], out["robust_at_origin"] = (
        (None, None) if out["ratio_robust_single"] is None
        or not kr.present(beyond.get("robust_at_origin")) else
        (int(beyond["robust_disagree"]), int(beyond["robust_at_origin"])))
    # Our fastest tree against the report's final variant: the two were
    # timed in different processes, each paired per round with Embree, so
    # their quotient through Embree (T_R final / T_R ours) cancels what a
    # process's speed does to both tracers alike.
    out["ratio_image"], out["runs_image"], out["image_tree"] = best_time_to_image(df, scene)
    out["ratio_beyond_over_final"] = _quotient(out["ratio_beyond"], out["ratio_final"])
    out["ratio_fast_over_final"] = _quotient(out["ratio_fast"], out["ratio_final"])
    return out


def time_to_image(r):
    """(Embree's time to image over ours, []) in the best modes, or (None,
    []): Embree's build plus its best render over our build (this record's
    tree) plus our best render. A record's renders are timed in rounds of
    every tracer, its builds after them in rounds of their own (each stops
    on its own time budget), so the best render is taken per render round
    (the fastest of each side's modes: ours are single rays, packets and,
    where the record has them, the second single-ray mode and the BVH over
    the leaves in single rays and in packets, with its build from the
    tree), then each term is
    the median of its rounds; there is no per-round spread to give."""
    if r is None:
        return None, []
    cols = ("T_B_runs", "T_R_runs", "T_R_fast_runs", "embree_T_B_runs", "embree_T_R_runs",
            "embree_packets_T_R_runs")
    lists = [r[c] for c in cols]
    if not all(isinstance(x, list) and x for x in lists):
        return None, []
    ours_b, ours_r, ours_f, emb_b, emb_r, emb_p = lists
    ours_modes = [ours_r, ours_f]
    single_origin = r["T_R_single_origin_runs"] if "T_R_single_origin_runs" in r else None
    if isinstance(single_origin, list) and single_origin:
        ours_modes.append(single_origin)
    # The BVH over the leaves: each render plus the BVH's build from the tree.
    for col in ("T_R_single_bvh_runs", "T_R_packets_bvh_runs"):
        bvh = r[col] if col in r else None
        if isinstance(bvh, list) and bvh:
            ours_modes.append([t + r["single_bvh_build_s"] for t in bvh])
    if len({len(x) for x in ours_modes + [emb_r, emb_p]}) != 1:
        return None, []
    ours = statistics.median(ours_b) + statistics.median(map(min, *ours_modes))
    emb = statistics.median(emb_b) + statistics.median(map(min, emb_r, emb_p))
    return emb / ours, []


def best_time_to_image(df, scene):
    """(ratio, runs, tree) of time_to_image for the tree of IMAGE_TREES that
    gives the image soonest on this scene, or (None, [], None). The trees
    are timed in processes of their own, so the larger of the two ratios also
    picks the luckier process where they are close (a bias of the order of
    their spread, not more)."""
    best = (None, [], None)
    for tree in IMAGE_TREES:
        ratio, runs = time_to_image(_with_embree(df, scene, tree))
        if ratio is not None and (best[0] is None or ratio > best[0]):
            best = (ratio, runs, tree)
    return best


def _quotient(a, b):
    return a / b if a is not None and b else None


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        recs = [(v, _compared(df, scene, v)) for v in kr.VARIANTS + kr.BEYOND]
        recs = [(v, r) for v, r in recs if r is not None]
        if recs:
            out.append(row(df, scene, recs))
    return out


# The figures' series: (row key, label, marker).
SERIES = [("single", "SAH-4 (sah-packet), single rays", "o"),
          ("fast", "SAH-4, fastest mode (packets)", "s"),
          ("best", "best mode / Embree's best", "D"),
          ("final", "Clipping pruning (the report's final)", "^"),
          ("tri_best", "baseline: BVH of whole triangles, best mode / Embree's best", "v")]
ROBUST_SERIES = [("single", "single rays / Embree's (default flags)", "o"),
                 ("robust_single", "single rays / robust Embree's", "s"),
                 ("best", "best mode / Embree's best (default flags)", "D"),
                 ("robust_best", "best mode / robust Embree's best", "^")]


def figure(ctx, data, filename="embree_ratio.pdf", series=SERIES):
    """Per scene, each series' paired ratio (point) and its range over the
    rounds (error bar), and a line at 1 (as fast as Embree)."""
    with plt.rc_context(figures.STYLE):
        fig, ax = plt.subplots(figsize=(6.3, 3.4))
        xs = list(range(1, len(data) + 1))
        for k, (key, label, marker) in enumerate(series):
            shift = 0.15 * (k - (len(series) - 1) / 2)
            pts = [(x + shift, r["ratio_" + key], r["runs_" + key] or [r["ratio_" + key]])
                   for x, r in zip(xs, data) if r["ratio_" + key] is not None]
            if pts:
                ys = [y for _, y, _ in pts]
                err = [[y - min(runs) for _, y, runs in pts],
                       [max(runs) - y for _, y, runs in pts]]
                ax.errorbar([x for x, _, _ in pts], ys, yerr=err, fmt=marker,
                            markersize=3.5, capsize=2, linewidth=0.8, label=label)
        ax.axhline(1.0, color="black", linewidth=0.8, linestyle="--")
        ax.set_xticks(xs)
        ax.set_xticklabels([r["scene"] for r in data], rotation=90, fontsize=6)
        ax.set_ylabel("Embree $T_R$ / kd-tree $T_R$ (paired per round)")
        ax.grid(axis="y", linewidth=0.4, alpha=0.5)
        if ax.get_legend_handles_labels()[1]:
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, 1.2), ncol=2,
                      frameon=False)
        else:
            ax.text(0.5, 0.5, "no paired ratios", ha="center", va="center",
                    transform=ax.transAxes)
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def ratio_macros(data, prefix, key):
    """Median, range and count of a ratio column over the scenes that have
    it, and how many of those of 50,000 triangles or more reach 0.7, 0.8
    (#23's bar for single rays) and 1.0 (its bar for the best modes)."""
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
        prefix + "BigAtLeastEighty": (str(sum(x >= 0.8 for x in big)), False),
        prefix + "BigAtLeastOne": (str(sum(x >= 1.0 for x in big)), False),
    }


def robust_at_origin_clause(data):
    """The report's sentence on the robust Embree's disagreements with our
    tree that start at a ray's origin, over the scenes whose records keep
    them; empty when none does (records from before 2026-12-06)."""
    kept = [r for r in data if r["robust_at_origin"] is not None]
    if not kept:
        return ""
    disagree = latex.fmt_int(sum(r["robust_disagree"] for r in kept))
    at_origin = latex.fmt_int(sum(r["robust_at_origin"] for r in kept))
    return ("Of the %s rays on which it and our tree disagree, %s start within rounding of "
            "the plane of the triangle it reports, as a shadow ray spawned from a surface "
            "(Section~\\ref{sec:robust}) does when this Embree finds it blocked where it "
            "starts, by the surface it leaves. " % (disagree, at_origin))


def million_macros(data, prefix, key):
    """How many scenes of a million triangles or more have the ratio, and on
    how many it is 1.0 or more (#23: time to image no longer than Embree's)."""
    values = [r[key] for r in data if r[key] is not None and r["n_tri"] >= 1000000]
    at_least_one = sum(x >= 1.0 for x in values)
    # The report's clause: a profile without such scenes says so, rather
    # than "on 0 of the 0 scenes".
    clause = ("on %d of the %d scenes of a million triangles or more, ours is as fast or faster"
              % (at_least_one, len(values)) if values else
              "none of these scenes has a million triangles or more")
    return {prefix + "MillionScenes": (str(len(values)), False),
            prefix + "MillionAtLeastOne": (str(at_least_one), False),
            prefix + "MillionClause": (clause, False)}


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the Embree table")
    data = rows(df)
    ctx.write("embree.tex", embree_tables.render(data))
    ctx.write("embree_rays.tex", embree_tables.render_rays(data))
    ctx.write("embree_robust.tex", embree_tables.render_robust(data))
    figure(ctx, data)
    figure(ctx, data, "embree_robust_ratio.pdf", ROBUST_SERIES)

    def total(key):
        return (latex.fmt_int(sum(r[key] for r in data)), False)

    return {
        **ratio_macros(data, "Embree", "ratio_final"),
        **ratio_macros(data, "EmbreePacket", "ratio_beyond"),
        **ratio_macros(data, "EmbreeSingle", "ratio_single"),
        **ratio_macros(data, "EmbreeFast", "ratio_fast"),
        **ratio_macros(data, "EmbreeBest", "ratio_best"),
        **ratio_macros(data, "EmbreeRobust", "ratio_robust_single"),
        **ratio_macros(data, "EmbreeRobustBest", "ratio_robust_best"),
        # Scenes on which the robust Embree answers a ray wrongly.
        "EmbreeRobustWrongScenes": (str(sum(1 for r in data if r["robust_wrong"]
                                            and sum(r["robust_wrong"]) > 0)), False),
        "EmbreeRobustAtOriginClause": (robust_at_origin_clause(data), True),
        **ratio_macros(data, "EmbreeImage", "ratio_image"),
        **million_macros(data, "EmbreeImage", "ratio_image"),
        # On how many scenes the binned tree gave the sooner image.
        "EmbreeImageBinnedScenes": (str(sum(r["image_tree"] == IMAGE_TREES[1] for r in data)),
                                    False),
        **{k: v for k, v in ratio_macros(data, "OursOverFinal", "ratio_beyond_over_final").items()
           if "Big" not in k},
        **{k: v for k, v in ratio_macros(data, "OursFastOverFinal", "ratio_fast_over_final").items()
           if "Big" not in k},
        "EmbreeOtherDisagreements": total("other"),
        "EmbreeGrazingDisagreements": total("grazing"),
        "EmbreeAtOriginDisagreements": total("at_origin"),
        "EmbreeKdWrong": total("kd_wrong"),
        "EmbreeEmbreeWrong": total("embree_wrong"),
    }
