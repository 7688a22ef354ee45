"""Accuracy versus time (issue 7): what each knob that buys tree accuracy
costs in time and what it gives, from results/accuracy.jsonl written by
experiments/run_accuracy.py (steps in experiments/accuracy.json).

Each record is one kdrt run (single thread) of one step on one scene: T_B
(build), T_R (render: primary + shadow rays), total time to image T_B + T_R,
the tree's SAH cost (K_T 15, K_I 20; cc/kdtree/stats.h), N_IT and N_TR per
ray, and mem (the report's formula, MB).

Output: accuracy_table.tex ("what each step of accuracy costs in time": per
step, the geometric mean over scenes of each quantity relative to the
report's clipping-pruning on the same scene, and the median of the absolute
times), accuracy_pareto.pdf (total time to image against SAH cost per scene,
the Pareto front drawn), accuracy_figure.tex (the figure environment) and
macros.
"""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import latex  # noqa: E402
from analysis import provenance  # noqa: E402

RESULTS_FILE = "accuracy.jsonl"
BASELINE = "report clipping-pruning"
QUANTITIES = [  # (key, header)
    ("T_B", "$T_B$"), ("T_R", "$T_R$"), ("total", "total"),
    ("sah_cost", "SAH"), ("N_IT", "$N_{IT}$"), ("N_TR", "$N_{TR}$"),
    ("mem_report_mb", "mem"),
]
MACROS = ["AccuracyScenes", "AccuracySteps", "AccuracyRuns",
          "AccuracyFastestStep", "AccuracyBestSahStep",
          "AccuracyExactBuildRatio", "AccuracyExactSahRatio",
          "AccuracyPerfectSahRatio", "AccuracyPerfectBuildRatio"]


def load(records):
    """{(scene, step): record} of the newest successful record, and the
    steps in the order first seen (the study's order)."""
    recs, steps = {}, []
    for r in records:
        if not r.get("ok"):
            continue
        r = dict(r)
        r["total"] = float(r["T_B"]) + float(r["T_R"])
        recs[(r["scene"], r["step"])] = r
        if (r["knob"], r["step"]) not in steps:
            steps.append((r["knob"], r["step"]))
    return recs, steps


def geomean(values):
    values = [v for v in values if v > 0]
    if not values:
        return float("nan")
    return math.exp(sum(math.log(v) for v in values) / len(values))


def median(values):
    values = sorted(values)
    if not values:
        return float("nan")
    n = len(values)
    return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])


def ratios(recs, scenes, step, key, base_step=BASELINE):
    """Per-scene ratio step / base_step of one quantity."""
    out = []
    for s in scenes:
        a, b = recs.get((s, step)), recs.get((s, base_step))
        if a and b and float(b[key]) > 0:
            out.append(float(a[key]) / float(b[key]))
    return out


def pareto(points):
    """Indices of the points (time, cost) that no other point beats in both."""
    front = []
    for i, (t, c) in enumerate(points):
        if not any((t2 <= t and c2 <= c) and (t2 < t or c2 < c)
                   for j, (t2, c2) in enumerate(points) if j != i):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def figure(ctx, recs, scenes, steps):
    # At most two panels a row, 3.2 in each: set at the text width (6.5 in),
    # not shrunk below 80 % (analysis/table_scale.py).
    cols = min(2, len(scenes))
    rows = int(math.ceil(len(scenes) / float(cols)))
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 3.0 * rows),
                             squeeze=False)
    knobs = []
    for k, _ in steps:
        if k not in knobs:
            knobs.append(k)
    markers = dict(zip(knobs, "osD^vP*X"))
    for ax, scene in zip([a for row in axes for a in row], scenes):
        pts, names = [], []
        for knob, step in steps:
            r = recs.get((scene, step))
            if not r:
                continue
            pts.append((r["total"], float(r["sah_cost"])))
            names.append(step)
            ax.scatter([r["total"]], [float(r["sah_cost"])],
                       marker=markers[knob], s=22,
                       label=knob if knob not in ax.get_legend_handles_labels()[1] else None)
        front = pareto(pts)
        ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front],
                color="black", linewidth=0.8, zorder=0)
        for i in front:
            ax.annotate(names[i], pts[i], fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
        ax.set_title(scene, fontsize=9)
        ax.set_xlabel("total time to image $T_B + T_R$ (s)", fontsize=8)
        ax.set_ylabel("SAH cost", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    for ax in [a for row in axes for a in row][len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(ctx.path("accuracy_pareto.pdf"))
    plt.close(fig)
    ctx.written.append("accuracy_pareto.pdf")
    ctx.write("accuracy_figure.tex",
              "\\begin{figure}[htbp]\\centering\n"
              "\\generatedfigure{accuracy_pareto.pdf}\n"
              "\\caption{Total time to image (single thread: build plus render "
              "of the primary and shadow rays) against the tree's SAH cost, one "
              "point per step of experiments/accuracy.json; the line joins the "
              "Pareto front (no other step is both faster and cheaper), whose "
              "steps are named.}\n\\label{fig:accuracy-pareto}\n\\end{figure}\n")


def generate(ctx):
    recs, steps = load(ctx.results(RESULTS_FILE))
    provenance.check(ctx, recs.values(), "the accuracy study (%s)" % RESULTS_FILE)
    scenes = sorted({s for s, _ in recs})
    if not recs:
        ctx.write("accuracy_table.tex", "\\emph{The accuracy-versus-time study "
                  "was not run (no results/accuracy.jsonl).}\n")
        ctx.write("accuracy_figure.tex", "")
        return {m: (latex.DASH, True) for m in MACROS}
    header = ["Knob", "Step"] + [h for _, h in QUANTITIES] + \
        ["$T_B$ (s)", "$T_R$ (s)"]
    body, last_knob = [], None
    for knob, step in steps:
        if last_knob is not None and knob != last_knob:
            body.append("midrule")
        last_knob = knob
        row = [latex.escape(knob), latex.escape(step)]
        for key, _ in QUANTITIES:
            row.append(latex.fmt_float(geomean(ratios(recs, scenes, step, key)),
                                       3))
        for key in ("T_B", "T_R"):
            row.append(latex.fmt_float(median(
                [float(recs[(s, step)][key]) for s in scenes
                 if (s, step) in recs]), 3))
        body.append(row)
    caption = ("What each step of accuracy costs in time, on %d scene%s "
               "(single thread). Columns 3--9: geometric mean over the scenes "
               "of the step's value divided by the report's clipping-pruning "
               "preset on the same scene (below 1: smaller). Last two columns: "
               "median over the scenes of the absolute times. ``bins'' steps "
               "are the full SAH (Wald \\& Havran 2006: $K_T = 15$, $K_I = 20$, "
               "empty bonus 0.8, cost termination, depth cap "
               "$8 + 1.3 \\log_2 N$) on x, y and z without clipping; the "
               "``clipping'' and ``pruning'' steps are the hybrid (128 bins "
               "above 4,096 references, exact sweep below) with clipping and "
               "pruning." % (len(scenes), "" if len(scenes) == 1 else "s"))
    ctx.write("accuracy_table.tex", latex.booktabs(
        header, body, align="ll" + "r" * (len(QUANTITIES) + 2),
        caption=caption, label="tab:accuracy", size="footnotesize"))
    figure(ctx, recs, scenes, steps)

    def best(key):
        scores = [(geomean(ratios(recs, scenes, st, key)), st)
                  for _, st in steps]
        scores = [x for x in scores if not math.isnan(x[0])]
        return latex.escape(min(scores)[1]) if scores else latex.DASH

    def rel(step, base, key):
        return latex.fmt_float(geomean(ratios(recs, scenes, step, key,
                                              base_step=base)), 3)
    return {
        "AccuracyScenes": (latex.fmt_int(len(scenes)), False),
        "AccuracySteps": (latex.fmt_int(len(steps)), False),
        "AccuracyRuns": (latex.fmt_int(len(recs)), False),
        "AccuracyFastestStep": (best("total"), True),
        "AccuracyBestSahStep": (best("sah_cost"), True),
        "AccuracyExactBuildRatio": (rel("exact sweep", "bins 32", "T_B"), False),
        "AccuracyExactSahRatio": (rel("exact sweep", "bins 32", "sah_cost"), False),
        "AccuracyPerfectSahRatio": (rel("perfect splits", "box clipping", "sah_cost"), False),
        "AccuracyPerfectBuildRatio": (rel("perfect splits", "box clipping", "T_B"), False),
    }
