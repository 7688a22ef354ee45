"""Triangles lying in a split plane: what the report's strict partition loses
(results/planar.jsonl from experiments/planar.py), the holes it leaves in the
image, and our default mode, which loses none.

Output: planar.tex (a table per variant: triangles lost, primary hits in
seed-compatible and default mode, pixels that differ), planar_seed.png and
planar_default.png (the variant that loses most), and macros.
"""

import os
import shutil

from analysis import kdtree_results as kr
from analysis import latex

PLANAR_FILE = "planar.jsonl"


def generate(ctx):
    recs = {}
    for r in ctx.results(PLANAR_FILE):
        if r.get("ok"):
            recs[(r["preset"], r["mode"])] = r
    names = ["PlanarScene", "PlanarWorstVariant", "PlanarWorstLost",
             "PlanarWorstHitsLost", "PlanarDefaultLost", "PlanarTriangles"]
    if not recs:
        ctx.write("planar.tex", "\\emph{The planar study was not run "
                  "(no results/planar.jsonl).}\n")
        ctx.write("planar_images.tex", "")
        return {n: (latex.DASH, True) for n in names}
    header = ["Variant", "Lost (seed mode)", "$P_{hit}$ seed",
              "$P_{hit}$ default", "Hits lost", "Lost (default)"]
    body, worst, default_lost, scene, n_tri = [], None, 0, "", 0
    for v in kr.VARIANTS:
        s, d = recs.get((v, "seed")), recs.get((v, "default"))
        if not s or not d:
            continue
        scene, n_tri = s["scene"], s.get("n_tri", 0)
        lost = int(s.get("N_lost_planar", 0))
        hits_lost = int(d["P_hit"]) - int(s["P_hit"])
        default_lost += int(d.get("N_lost_planar", 0))
        body.append([latex.escape(kr.TITLES[v]), latex.fmt_int(lost),
                     latex.fmt_int(s["P_hit"]), latex.fmt_int(d["P_hit"]),
                     latex.fmt_int(hits_lost),
                     latex.fmt_int(d.get("N_lost_planar", 0))])
        if worst is None or hits_lost > worst[2]:
            worst = (v, lost, hits_lost, s, d)
    caption = ("Triangles lying in a split plane on a voxel world (every "
               "face on an integer plane). ``Lost'': references the strict "
               "partition of the seed-compatible mode sends to neither child "
               "(a triangle is missing from the image only if all its "
               "references are lost). ``Hits lost'': primary rays that hit "
               "in our default mode but miss in the seed mode.")
    ctx.write("planar.tex", latex.booktabs(header, body, align="lrrrrr",
                                           caption=caption, label="tab:planar",
                                           size="footnotesize"))
    images = ""
    if worst and worst[3].get("image") and worst[4].get("image") and \
            os.path.exists(worst[3]["image"]) and \
            os.path.exists(worst[4]["image"]):
        shutil.copy(worst[3]["image"], ctx.path("planar_seed.png"))
        shutil.copy(worst[4]["image"], ctx.path("planar_default.png"))
        ctx.written += ["planar_seed.png", "planar_default.png"]
        images = ("\\begin{figure}[htbp]\\centering\n"
                  "\\includegraphics[width=0.48\\linewidth]{generated/planar_seed.png}\\hfill\n"
                  "\\includegraphics[width=0.48\\linewidth]{generated/planar_default.png}\n"
                  "\\caption{%s, %s: seed-compatible mode (left; holes where "
                  "in-plane triangles were lost) and our default (right).}\n"
                  "\\label{fig:planar}\n\\end{figure}\n"
                  % (latex.escape(scene), latex.escape(kr.TITLES[worst[0]])))
    ctx.write("planar_images.tex", images)
    return {
        "PlanarScene": (latex.escape(scene), True),
        "PlanarTriangles": (latex.fmt_int(n_tri), False),
        "PlanarWorstVariant": (latex.escape(kr.TITLES[worst[0]]) if worst
                               else latex.DASH, True),
        "PlanarWorstLost": (latex.fmt_int(worst[1]) if worst else latex.DASH,
                            True),
        "PlanarWorstHitsLost": (latex.fmt_int(worst[2]) if worst
                                else latex.DASH, True),
        "PlanarDefaultLost": (latex.fmt_int(default_lost), False),
    }
