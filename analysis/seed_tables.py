"""The report's own tables (analysis/seed/*.csv), set next to what this
reproduction has in their place.

Output: seed_table1.tex (the report's 18 scenes, with our stand-in for each).
"""

from analysis import latex
from analysis import table1


def stand_ins(ctx):
    """{report_scene: [row, ...]} for our successfully loaded scenes."""
    rows = table1.build_rows(ctx.manifest, ctx.results(table1.SCENES_FILE))
    out = {}
    for row in rows:
        number = row["scene"].get("report_scene")
        if row["ok"] and number not in (None, ""):
            out.setdefault(int(number), []).append(row)
    return out


def render_table1(seed, ours):
    groups = [("", 2), ("The report", 5), ("This reproduction", 2)]
    header = ["\\#", "Scene", "$N_{tri}$", "$P_{hit}$", "$P_{miss}$",
              "$S_{hit}$", "$S_{miss}$", "Our scene", "Triangles"]
    body = []
    for number, rec in seed.iterrows():
        mine = ours.get(int(number), [])
        body.append([
            str(int(number)),
            latex.escape(rec["name"]),
            latex.fmt_int(int(rec["n_tri"])),
            latex.fmt_int(int(rec["p_hit"])),
            latex.fmt_int(int(rec["p_miss"])),
            latex.fmt_int(int(rec["s_hit"])),
            latex.fmt_int(int(rec["s_miss"])),
            ", ".join("%s %s" % (r["number"], latex.escape(r["name"]))
                      for r in mine) or latex.DASH,
            ", ".join(latex.fmt_int(r["n_tri"]) for r in mine) or latex.DASH,
        ])
    caption = (
        "The report's scenes: its Table~1 as printed (800$\\times$800 "
        "primary rays, one shadow ray per primary hit), and the scene of "
        "this reproduction that stands in for each (Table~\\ref{tab:scenes}). "
        "The ray counts are the report's; ours come with the kd-tree runs.")
    return latex.booktabs(header, body, align="rlrrrrrlr", groups=groups,
                          caption=caption, label="tab:seed1",
                          size="footnotesize")


def generate(ctx):
    seed = ctx.seed_table1
    ctx.write("seed_table1.tex", render_table1(seed, stand_ins(ctx)))
    return {}
