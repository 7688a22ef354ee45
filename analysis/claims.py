"""The report's findings, each checked against our runs.

Every claim the report states in its captions and text becomes a test on one
scene's numbers; a claim is confirmed when at least two thirds of the scenes
with both variants agree, refuted when at most one third do, mixed otherwise.
Output: claims.tex (a table: claim, test, scenes agreeing, median ratio,
verdict) and macros with the counts.
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex


def _v(df, scene, variant, column):
    if (scene, variant) not in df.index:
        return None
    value = df.loc[(scene, variant)][column]
    if value is None or value != value:
        return None
    return float(value)


def _ratio(a, b):
    return a / b if a is not None and b not in (None, 0) else None


# (id, where, the report's words, our test in words, variants, test(get) ->
#  (agrees: bool, ratio: float or None))
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
     lambda g: (g("binning-8-driving", "T_B") < g("binning-8", "T_B")
                and g("binning-8-driving", "T_R") <= 1.15 * g("binning-8", "T_R"),
                _ratio(g("binning-8-driving", "T_B"), g("binning-8", "T_B")))),
    ("bins", "Table 3",
     "More bins have no negative effect on the build times.",
     "$T_B$(B32) $\\le$ 1.15 $T_B$(B8); ratio",
     lambda g: (g("binning-32", "T_B") <= 1.15 * g("binning-8", "T_B"),
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
     lambda g: (g("clipping-pruning", "T_R") >= 0.97 * g("pruning", "T_R"),
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
     lambda g: (g("binning-8-driving", "T_B") <
                min(g("binning-8", "T_B"), g("binning-32", "T_B")),
                _ratio(g("binning-8-driving", "T_B"),
                       min(g("binning-8", "T_B"), g("binning-32", "T_B"))))),
    ("clipbuildcost", "Figure 1",
     "Clipping and pruning take a little more build time than binning, not "
     "significantly more.",
     "$T_B$(clip+prune) $\\le$ 1.5 $T_B$(B8 driving); ratio",
     lambda g: (g("clipping-pruning", "T_B") <=
                1.5 * g("binning-8-driving", "T_B"),
                _ratio(g("clipping-pruning", "T_B"),
                       g("binning-8-driving", "T_B")))),
    ("clipfastest", "Figure 2",
     "The clipping/pruning configurations are the fastest to render and "
     "surpass the binning ones.",
     "min $T_R$ of clipping, pruning, clip+prune $<$ min $T_R$ of the three "
     "binnings; ratio",
     lambda g: (min(g(v, "T_R") for v in kr.GROUPS[2]) <
                min(g(v, "T_R") for v in kr.GROUPS[1]),
                _ratio(min(g(v, "T_R") for v in kr.GROUPS[2]),
                       min(g(v, "T_R") for v in kr.GROUPS[1])))),
]


def evaluate(df):
    """[(claim, agree, total, median_ratio, verdict)]."""
    scenes = kr.scenes_in_order(df)
    out = []
    for claim in CLAIMS:
        test = claim[4]
        agree = total = 0
        ratios = []
        for scene in scenes:
            def g(variant, column, scene=scene):
                value = _v(df, scene, variant, column)
                if value is None:
                    raise LookupError
                return value
            try:
                ok, ratio = test(g)
            except (LookupError, ZeroDivisionError):
                continue
            total += 1
            agree += int(bool(ok))
            if ratio is not None:
                ratios.append(ratio)
        if total == 0:
            verdict = "not tested"
        elif agree * 3 >= total * 2:
            verdict = "confirmed"
        elif agree * 3 <= total:
            verdict = "refuted"
        else:
            verdict = "mixed"
        median = statistics.median(ratios) if ratios else None
        out.append((claim, agree, total, median, verdict))
    return out


def render(results):
    header = ["Where", "The report says", "Our test (per scene)", "Agree",
              "Median ratio", "Verdict"]
    body = []
    for claim, agree, total, median, verdict in results:
        body.append([claim[1], claim[2], claim[3],
                     "%d/%d" % (agree, total),
                     latex.fmt_float(median, 3) if median is not None
                     else latex.DASH,
                     "\\textbf{%s}" % verdict])
    caption = ("The report's findings checked on our runs. A claim is "
               "confirmed when at least two thirds of the scenes agree, "
               "refuted when at most one third do.")
    return latex.booktabs(header, body,
                          align="l p{4.2cm} p{4.2cm} r r l",
                          caption=caption, label="tab:claims",
                          size="scriptsize")


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    results = evaluate(df)
    ctx.write("claims.tex", render(results))
    counts = {"confirmed": 0, "refuted": 0, "mixed": 0, "not tested": 0}
    for *_, verdict in results:
        counts[verdict] += 1
    return {"ClaimsTotal": (str(len(results)), False),
            "ClaimsConfirmed": (str(counts["confirmed"]), False),
            "ClaimsRefuted": (str(counts["refuted"]), False),
            "ClaimsMixed": (str(counts["mixed"]), False)}
