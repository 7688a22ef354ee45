"""The report's Tables 2-10 from our kd-tree runs: three sets (times and
traversal; tree size; depth, clipping, pruning) of three tables (spatial
median, binning, clipping/pruning), each three variants side by side.

Output: table2.tex ... table10.tex, and table1_rays.tex (the ray counts
of the report's Table 1 for our scenes).
"""

from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

SETS = [
    # (first table number, columns, caption stem)
    (2, [("T_B", "$T_B$", "time"), ("T_R", "$T_R$", "time"),
         ("perf", "$\\mathit{perf}$", "int"), ("N_IT", "$N_{IT}$", "f2"),
         ("N_TR", "$N_{TR}$", "f2")],
     "$T_B$: build time (s); $T_R$: render time of all rays (s); "
     "$\\mathit{perf}$: 640,000 primary rays / $T_R$ in krays/s (the "
     "report's definition); $N_{IT}$: intersection tests per ray; "
     "$N_{TR}$: inner nodes visited per ray."),
    (5, [("N_I", "$N_I$", "int"), ("N_L", "$N_L$", "int"),
         ("N_TP", "$N_{TP}$", "int"), ("N_AP", "$N_{AP}$", "f2"),
         ("mem", "$\\mathit{mem}$", "f3")],
     "$N_I$: inner nodes; $N_L$: leaves; $N_{TP}$: references in leaves; "
     "$N_{AP}$: references per leaf; $\\mathit{mem}$: MB by the report's "
     "formula."),
    (8, [("R_E", "$R_E$", "f2"), ("D_max", "$D_{max}$", "int"),
         ("D_avg", "$D_{avg}$", "f1"), ("N_CL", "$N_{CL}$", "int"),
         ("N_PR", "$N_{PR}$", "int")],
     "$R_E$: empty leaves / leaves; $D_{max}$, $D_{avg}$: maximum and "
     "average leaf depth; $N_{CL}$: clipped triangles; $N_{PR}$: pruned "
     "triangles."),
]
def fmt(kind, value):
    if value is None or value != value:  # None or NaN
        return latex.DASH
    if kind == "int":
        return latex.fmt_int(int(round(float(value))))
    if kind == "time":
        return latex.fmt_float(float(value), 3)
    if kind == "f1":
        return format(float(value), ".1f")
    if kind == "f2":
        return format(float(value), ",.2f")
    if kind == "f3":
        return format(float(value), ",.3f")
    raise ValueError(kind)


def render(df, scenes, variants, columns, caption, label):
    header = ["\\#", "Scene"] + [h for _ in variants for _, h, _ in columns]
    groups = [("", 2)] + [(latex.escape(kr.TITLES[v]), len(columns))
                          for v in variants]
    body = []
    for i, scene in enumerate(scenes):
        row = [str(i + 1), latex.escape(scene)]
        for v in variants:
            rec = df.loc[(scene, v)] if (scene, v) in df.index else None
            for name, _, kind in columns:
                row.append(fmt(kind, None if rec is None else rec[name]))
        body.append(row)
    if not body:
        body = [["", "\\emph{no kd-tree runs}"] + [""] * (len(header) - 2)]
    return latex.booktabs(header, body, align="rl" + "r" * (len(header) - 2),
                          groups=groups, caption=caption, label=label,
                          size="footnotesize")  # on landscape pages (report/main.tex)


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    cpus = provenance.cpus(provenance.check_frame(
        ctx, df, "the kd-tree tables (%s)" % kr.KDTREE_FILE))
    scenes = kr.scenes_in_order(df)
    for first, columns, stem in SETS:
        for k, variants in enumerate(kr.GROUPS):
            number = first + k
            caption = ("Ours, as the report's Table~%d (%s). %s"
                       % (number, kr.GROUP_NAMES[k], stem))
            ctx.write("table%d.tex" % number,
                      render(df, scenes, variants, columns, caption,
                             "tab:t%d" % number))
    ctx.write("table1_rays.tex", render_rays(df, scenes))
    macros = timing_macros(df)
    macros.update({
            "KdCpus": (latex.escape("; ".join(cpus)) or latex.DASH, True),
            "NumKdScenes": (str(len(scenes)), False),
            # The report's nine only (not kr.BEYOND).
            "NumKdRuns": (str(sum(1 for key in df.index
                                  if isinstance(key, tuple) and key[1] in kr.VARIANTS)),
                          False)})
    return macros


def timing_macros(df):
    """How the timings were taken, from the records themselves: repeats asked,
    the repeat budget, the fewest runs any timed step got, and how many kdrt
    processes ran at once."""
    def ints(col):
        return [int(v) for v in df[col].tolist()
                if v is not None and v == v] if col in df else []
    runs = [len(v) for col in ("T_B_runs", "T_R_runs") if col in df
            for v in df[col].tolist() if isinstance(v, list)]
    budgets = sorted({float(v) for v in df["repeat_budget_s"].tolist()
                      if v is not None and v == v and float(v) > 0}) \
        if "repeat_budget_s" in df else []
    repeats, jobs = ints("repeats"), ints("concurrent_jobs")
    return {
        "TimingRepeats": (str(max(repeats)) if repeats else latex.DASH, True),
        "TimingBudget": (
            ("A timed step stops repeating once its runs took %s\\,s in all "
             "(so the largest scenes' steps are timed fewer times)."
             % "/".join("%g" % b for b in budgets)) if budgets
            else "Every timed step ran all its repeats.", True),
        "TimingMinRuns": (str(min(runs)) if runs else latex.DASH, True),
        "TimingJobs": (str(max(jobs)) if jobs else "1", False),
    }


def render_rays(df, scenes):
    """The report's Table 1 ray counts for our scenes (from one variant's run:
    hits do not depend on the variant, which the tests check)."""
    header = ["\\#", "Scene", "$N_{tri}$", "$P_{hit}$", "$P_{miss}$",
              "$S_{hit}$", "$S_{miss}$"]
    body = []
    for i, scene in enumerate(scenes):
        rec = None
        for v in reversed(kr.VARIANTS):
            if (scene, v) in df.index:
                rec = df.loc[(scene, v)]
                break
        body.append([str(i + 1), latex.escape(scene)] +
                    [fmt("int", rec[c]) for c in
                     ("n_tri", "P_hit", "P_miss", "S_hit", "S_miss")])
    if not body:
        body = [["", "\\emph{no kd-tree runs}", "", "", "", "", ""]]
    caption = ("Our scenes as the report's Table~1: primary rays that hit "
               "and miss, and shadow rays (one per primary hit and light) "
               "that hit and miss. A scene without a light casts no shadow "
               "ray.")
    return latex.booktabs(header, body, align="rlrrrrr", caption=caption,
                          label="tab:rays", size="footnotesize")
