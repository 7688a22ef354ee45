"""The report's findings, each checked against our runs.

Every claim the report states in its captions and text becomes a test on one
scene's numbers. A timing claim compares all the timed rounds of each side
(columns T_B_runs, T_R_runs): where the two sides' ranges [min, max] overlap,
or a side has fewer than 2 runs (no spread is known), that scene is "within
noise", neither agreeing nor disagreeing. A claim is "within noise" when at
least half of its tested scenes are; otherwise it is confirmed when at least
two thirds of the decided scenes agree, refuted when at most one third do,
mixed in between. Output: claims.tex (a table: claim, test, scenes agreeing
of those decided, scenes within noise, median ratio of the medians,
verdict), claims_brief.tex (one line per claim, for the findings page),
claims_ratios.pdf (each claim's ratio per scene against the line where it
changes side) and macros with the counts.
"""

import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import figures  # noqa: E402
from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

VERDICTS = ["confirmed", "refuted", "mixed", "within noise", "not tested"]


def _v(df, scene, variant, column):
    if (scene, variant) not in df.index:
        return None
    value = df.loc[(scene, variant)][column]
    if value is None or value != value:
        return None
    return float(value)


def _ratio(a, b):
    return a / b if a is not None and b not in (None, 0) else None


class Scene:
    """One scene's numbers for the tests: g(variant, column) is a value (a
    median for a timing), g.runs(variant, column) all its timed rounds;
    either raises LookupError when missing."""

    def __init__(self, df, scene):
        self.df, self.scene = df, scene

    def __call__(self, variant, column):
        value = _v(self.df, self.scene, variant, column)
        if value is None:
            raise LookupError
        return value

    def runs(self, variant, column):
        self(variant, column)  # the median must be there
        runs = self.df.loc[(self.scene, variant)][column + "_runs"]
        return [float(x) for x in runs] if isinstance(runs, list) else []


def below(a, b, factor=1.0):
    """Whether runs a lie below factor * runs b: True or False when the
    ranges are apart, None (within noise) when they overlap or a side has
    fewer than 2 runs."""
    if len(a) < 2 or len(b) < 2:
        return None
    if max(a) < factor * min(b):
        return True
    if min(a) > factor * max(b):
        return False
    return None


def all3(*values):
    """Three-valued and: False if any is False, else None if any is None."""
    if any(v is False for v in values):
        return False
    return None if any(v is None for v in values) else True


def any3(*values):
    """Three-valued or: True if any is True, else None if any is None."""
    if any(v is True for v in values):
        return True
    return None if any(v is None for v in values) else False


def not3(value):
    return None if value is None else not value


def fastest_below(g, group_a, group_b, column):
    """min over group_a < min over group_b, on the runs: some variant of a
    lies below every variant of b."""
    return any3(*[all3(*[below(g.runs(a, column), g.runs(b, column))
                         for b in group_b]) for a in group_a])


# (id, where, the report's words, our test in words, test(g) -> (agrees:
#  True, False or None for within noise, ratio of the medians or None)).
CLAIMS = [
    ("depth", "Table 2",
     "A depth of 24 dramatically decreases intersection tests and increases "
     "inner node visits.",
     "$N_{IT}$(24/2) $<$ $N_{IT}$(16/2) and $N_{TR}$(24/2) $>$ $N_{TR}$(16/2); "
     "ratio of $N_{IT}$",
     lambda g: (g("median-24-2", "N_IT") < g("median-16-2", "N_IT")
                and g("median-24-2", "N_TR") > g("median-16-2", "N_TR"),
                _ratio(g("median-24-2", "N_IT"), g("median-16-2", "N_IT")))),
    ("leafrefs", "Table 5",
     "Depth 24 dramatically decreases the references per leaf.",
     "$N_{AP}$(24/2) $<$ $N_{AP}$(16/2); ratio",
     lambda g: (g("median-24-2", "N_AP") < g("median-16-2", "N_AP"),
                _ratio(g("median-24-2", "N_AP"), g("median-16-2", "N_AP")))),
    ("emptyleaves", "Table 8",
     "The empty-leaf ratio is lower with maxLeafSize 8.",
     "$R_E$(24/8) $<$ $R_E$(24/2); ratio",
     lambda g: (g("median-24-8", "R_E") < g("median-24-2", "R_E"),
                _ratio(g("median-24-8", "R_E"), g("median-24-2", "R_E")))),
    ("notmaxdepth", "Table 8",
     "In many scenes most leaves do not reach the maximum depth.",
     "$D_{avg}$ $<$ $D_{max}$ $-$ 1 for 24/8; ratio $D_{avg}/D_{max}$",
     lambda g: (g("median-24-8", "D_avg") < g("median-24-8", "D_max") - 1,
                _ratio(g("median-24-8", "D_avg"), g("median-24-8", "D_max")))),
    ("drivingbuild", "Table 3",
     "The driving axis builds faster while keeping high ray-tracing "
     "performance.",
     "$T_B$(B8 driving) $<$ $T_B$(B8) and $T_R$ within 15\\%; ratio of $T_B$",
     lambda g: (all3(below(g.runs("binning-8-driving", "T_B"),
                          g.runs("binning-8", "T_B")),
                    below(g.runs("binning-8-driving", "T_R"),
                          g.runs("binning-8", "T_R"), 1.15)),
                _ratio(g("binning-8-driving", "T_B"), g("binning-8", "T_B")))),
    ("bins", "Table 3",
     "More bins have no negative effect on the build times.",
     "$T_B$(B32) $\\le$ 1.15 $T_B$(B8); ratio",
     lambda g: (below(g.runs("binning-32", "T_B"), g.runs("binning-8", "T_B"),
                      1.15),
                _ratio(g("binning-32", "T_B"), g("binning-8", "T_B")))),
    ("allaxes", "Table 6",
     "All three axes reduce the number of leaves and the memory.",
     "$N_L$ and $\\mathit{mem}$ of B8 $<$ those of B8 driving; ratio of $N_L$",
     lambda g: (g("binning-8", "N_L") < g("binning-8-driving", "N_L")
                and g("binning-8", "mem") < g("binning-8-driving", "mem"),
                _ratio(g("binning-8", "N_L"), g("binning-8-driving", "N_L")))),
    ("binningalike", "Table 9",
     "There is not much difference between the three binning variants.",
     "$R_E$ and $D_{avg}$ of the three within 25\\%; ratio max/min $D_{avg}$",
     lambda g: (max(g(v, "R_E") for v in kr.GROUPS[1]) <=
                1.25 * max(min(g(v, "R_E") for v in kr.GROUPS[1]), 1e-9)
                and max(g(v, "D_avg") for v in kr.GROUPS[1]) <=
                1.25 * min(g(v, "D_avg") for v in kr.GROUPS[1]),
                _ratio(max(g(v, "D_avg") for v in kr.GROUPS[1]),
                       min(g(v, "D_avg") for v in kr.GROUPS[1])))),
    ("clipnotbetter", "Table 4",
     "Clipping and pruning together do not make a better tree than pruning "
     "alone.",
     "$T_R$(clip+prune) $\\ge$ 0.97 $T_R$(prune); ratio",
     lambda g: (not3(below(g.runs("clipping-pruning", "T_R"),
                           g.runs("pruning", "T_R"), 0.97)),
                _ratio(g("clipping-pruning", "T_R"), g("pruning", "T_R")))),
    ("manyclipped", "Table 10",
     "Clipping produces an extraordinary number of clipped triangles, in "
     "some scenes a multiple of the triangle count.",
     "$N_{CL}$(clipping) $>$ $N_{tri}$; ratio $N_{CL}/N_{tri}$",
     lambda g: (g("clipping", "N_CL") > g("clipping", "n_tri"),
                _ratio(g("clipping", "N_CL"), g("clipping", "n_tri")))),
    ("fewerpruned", "Table 10",
     "Fewer triangles are pruned when clipping is also on.",
     "$N_{PR}$(clip+prune) $<$ $N_{PR}$(prune); ratio",
     lambda g: (g("clipping-pruning", "N_PR") < g("pruning", "N_PR"),
                _ratio(g("clipping-pruning", "N_PR"), g("pruning", "N_PR")))),
    ("drivingfastest", "Figure 1",
     "Binning on the driving axis builds faster than the two all-axes "
     "binnings.",
     "$T_B$(B8 driving) $<$ min($T_B$(B8), $T_B$(B32)); ratio to the min",
     lambda g: (all3(*[below(g.runs("binning-8-driving", "T_B"),
                             g.runs(v, "T_B")) for v in ("binning-8", "binning-32")]),
                _ratio(g("binning-8-driving", "T_B"),
                       min(g("binning-8", "T_B"), g("binning-32", "T_B"))))),
    ("clipbuildcost", "Figure 1",
     "Clipping and pruning take a little more build time than binning, not "
     "significantly more.",
     "$T_B$(clip+prune) $\\le$ 1.5 $T_B$(B8 driving); ratio",
     lambda g: (below(g.runs("clipping-pruning", "T_B"),
                      g.runs("binning-8-driving", "T_B"), 1.5),
                _ratio(g("clipping-pruning", "T_B"),
                       g("binning-8-driving", "T_B")))),
    ("clipfastest", "Figure 2",
     "The clipping/pruning configurations are the fastest to render and "
     "surpass the binning ones.",
     "min $T_R$ of clipping, pruning, clip+prune $<$ min $T_R$ of the three "
     "binnings; ratio",
     lambda g: (fastest_below(g, kr.GROUPS[2], kr.GROUPS[1], "T_R"),
                _ratio(min(g(v, "T_R") for v in kr.GROUPS[2]),
                       min(g(v, "T_R") for v in kr.GROUPS[1])))),
]


# Where each claim's ratio (the test's last column) changes side, and on
# which side the report is right ("below" or "above"), for the figure. A
# claim with two conditions shows its ratio's; notmaxdepth's line moves with
# D_max (1 - 1/24 at the depth cap of 24).
THRESHOLDS = {
    "depth": (1.0, "below"), "leafrefs": (1.0, "below"),
    "emptyleaves": (1.0, "below"), "notmaxdepth": (1 - 1 / 24, "below"),
    "drivingbuild": (1.0, "below"), "bins": (1.15, "below"),
    "allaxes": (1.0, "below"), "binningalike": (1.25, "below"),
    "clipnotbetter": (0.97, "above"), "manyclipped": (1.0, "above"),
    "fewerpruned": (1.0, "below"), "drivingfastest": (1.0, "below"),
    "clipbuildcost": (1.5, "below"), "clipfastest": (1.0, "below"),
}

# Each claim in a few words, for the findings page (claims_brief.tex).
SHORT = {
    "depth": "depth 24 cuts triangle tests, adds node visits",
    "leafrefs": "depth 24 cuts the references per leaf",
    "emptyleaves": "leaf size 8 lowers the share of empty leaves",
    "notmaxdepth": "most leaves stop above the maximum depth",
    "drivingbuild": "the driving axis builds faster, renders as fast",
    "bins": "32 bins build no slower than 8",
    "allaxes": "all three axes: fewer leaves, less memory",
    "binningalike": "the three binnings differ little",
    "clipnotbetter": "clipping adds nothing to pruning",
    "manyclipped": "clipping clips more triangles than the scene has",
    "fewerpruned": "fewer triangles pruned with clipping on",
    "drivingfastest": "the driving axis builds fastest of the binnings",
    "clipbuildcost": "clipping and pruning cost little build time",
    "clipfastest": "the clipping/pruning variants render fastest",
}


def verdict(agree, decided, noise):
    """Within noise when at least half the tested scenes are; else two
    thirds of the decided scenes confirm, one third or fewer refute."""
    if decided + noise == 0:
        return "not tested"
    if noise * 2 >= decided + noise:
        return "within noise"
    if agree * 3 >= decided * 2:
        return "confirmed"
    return "refuted" if agree * 3 <= decided else "mixed"


def evaluate(df, per_scene=None):
    """[(claim, agree, decided, noise, median_ratio, verdict)]; with
    per_scene (a dict), per_scene[claim id] = the scenes' ratios."""
    out = []
    for claim in CLAIMS:
        agree = decided = noise = 0
        ratios = []
        if per_scene is not None:
            per_scene[claim[0]] = ratios
        for scene in kr.scenes_in_order(df):
            try:
                ok, ratio = claim[4](Scene(df, scene))
            except (LookupError, ZeroDivisionError):
                continue
            if ok is None:
                noise += 1
            else:
                decided += 1
                agree += int(bool(ok))
            if ratio is not None:
                ratios.append(ratio)
        median = statistics.median(ratios) if ratios else None
        out.append((claim, agree, decided, noise, median,
                    verdict(agree, decided, noise)))
    return out


def render(results):
    header = ["Where", "The report says", "Our test (per scene)",
              "Agree", "Noise", "Median", "Verdict"]
    body = []
    for claim, agree, decided, noise, median, verdict_ in results:
        body.append([claim[1], claim[2], claim[3],
                     "%d/%d" % (agree, decided), str(noise),
                     latex.fmt_float(median, 3) if median is not None
                     else latex.DASH,
                     "\\textbf{%s}" % verdict_])
    caption = ("The report's findings checked on our runs. A timing test "
               "compares every timed round of the two sides: a scene whose "
               "two ranges of runs (min to max) overlap, or with fewer than "
               "two runs on a side, is within noise and neither agrees nor "
               "disagrees. A claim is within noise when at least half of its "
               "scenes are; otherwise it is confirmed when at least two "
               "thirds of the decided scenes agree, refuted when at most one "
               "third do, and mixed in between. The median ratio is taken "
               "over the medians of the runs. Agree: scenes that agree / scenes "
               "decided; Noise: scenes within noise; Median: the median ratio.")
    return latex.booktabs(header, body,
                          align="l p{4.2cm} p{4.2cm} r r r l",
                          caption=caption, label="tab:claims",
                          size="footnotesize")


def figure(ctx, results, per_scene, filename="claims_ratios.pdf"):
    """Each claim's ratio per scene (dots) and median (bar) on a log axis,
    against the line where the claim changes side (red; the arrow points to
    the side where the report is right)."""
    with plt.rc_context(figures.STYLE):
        fig, ax = plt.subplots(figsize=(6.3, 0.27 * len(results) + 0.8))
        for y, (claim, _, _, _, median, verdict_) in enumerate(results):
            ratios = [r for r in per_scene.get(claim[0], []) if r and r > 0]
            ax.plot(ratios, [y] * len(ratios), "o", markersize=2.4, color="0.45", alpha=0.7)
            if median:
                ax.plot([median], [y], "|", markersize=9, color="black", markeredgewidth=1.3)
            line, side = THRESHOLDS[claim[0]]
            ax.plot([line], [y], "<" if side == "below" else ">", color="#c0392b", markersize=5)
            ax.plot([line, line], [y - 0.35, y + 0.35], color="#c0392b", linewidth=1)
        ax.set_yticks(range(len(results)))
        ax.set_yticklabels(["%s: %s (%s)" % (c[1], SHORT[c[0]], v)
                            for c, *_, v in results], fontsize=6.5)
        ax.invert_yaxis()
        ax.set_xscale("log")
        ax.set_xlabel("the test's ratio per scene (log)")
        ax.grid(axis="x", which="major", linewidth=0.4, alpha=0.5)
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def render_brief(results):
    """One line per claim for the findings page: where, the claim in a few
    words, the verdict, scenes agreeing of those decided."""
    lines = ["\\begin{tabular}{@{}l l l r@{}}"]
    for claim, agree, decided, noise, _, verdict_ in results:
        lines.append("%s & %s & \\textbf{%s} & %d/%d%s \\\\"
                     % (claim[1], SHORT[claim[0]], verdict_, agree, decided,
                        " (%d in noise)" % noise if noise else ""))
    lines.append("\\end{tabular}")
    return "\n".join(lines) + "\n"


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the claims table")
    per_scene = {}
    results = evaluate(df, per_scene)
    ctx.write("claims.tex", render(results))
    figure(ctx, results, per_scene)
    ctx.write("claims_brief.tex", render_brief(results))
    counts = dict.fromkeys(VERDICTS, 0)
    for *_, verdict_ in results:
        counts[verdict_] += 1
    return {"ClaimsTotal": (str(len(results)), False),
            "ClaimsConfirmed": (str(counts["confirmed"]), False),
            "ClaimsRefuted": (str(counts["refuted"]), False),
            "ClaimsMixed": (str(counts["mixed"]), False),
            "ClaimsWithinNoise": (str(counts["within noise"]), False)}
