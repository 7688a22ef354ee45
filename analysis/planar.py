"""Triangles lying in a split plane: what the report's strict partition loses
(results/planar.jsonl from experiments/run_planar.py), the holes it leaves in the
image, and our default mode, which loses none.

Output: planar.tex (a table per variant: references lost, primary hits in
seed-compatible and default mode, pixels that differ), planar_seed.png,
planar_default.png and planar_diff.png (the variant whose image differs
most), and macros.
"""

import os
import shutil

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

from analysis import kdtree_results as kr  # noqa: E402
from analysis import latex  # noqa: E402
from analysis import provenance  # noqa: E402


def pixel_diff(seed_png, default_png):
    """(number of pixels that differ, difference image): the default image
    dimmed, with every differing pixel in red."""
    a = mpimg.imread(seed_png)[..., :3]
    b = mpimg.imread(default_png)[..., :3]
    if a.shape != b.shape:
        raise ValueError("%s and %s differ in size" % (seed_png, default_png))
    mask = np.any(a != b, axis=-1)
    diff = b * 0.35
    diff[mask] = [1.0, 0.0, 0.0]
    return int(mask.sum()), diff

PLANAR_FILE = "planar.jsonl"


def generate(ctx):
    recs = {}
    for r in ctx.results(PLANAR_FILE):
        if r.get("ok"):
            recs[(r["preset"], r["mode"])] = r
    # Counts and hits only, no timings: the code must be one, the build may
    # be any.
    provenance.check(ctx, recs.values(), "the planar study (%s)" % PLANAR_FILE,
                     timings=False)
    names = ["PlanarScene", "PlanarWorstVariant", "PlanarWorstLost",
             "PlanarWorstPixels", "PlanarDefaultLost", "PlanarTriangles"]
    if not recs:
        ctx.write("planar.tex", "\\emph{The planar study was not run "
                  "(no results/planar.jsonl).}\n")
        ctx.write("planar_images.tex", "")
        return {n: (latex.DASH, True) for n in names}
    header = ["Variant", "Lost (seed mode)", "$P_{hit}$ seed",
              "$P_{hit}$ default", "Hits lost", "Pixels differing",
              "Lost (default)"]
    body, worst, default_lost, scene, n_tri = [], None, 0, "", 0
    for v in kr.VARIANTS:
        s, d = recs.get((v, "seed")), recs.get((v, "default"))
        if not s or not d:
            continue
        scene, n_tri = s["scene"], s.get("n_tri", 0)
        lost = int(s.get("N_lost_planar", 0))
        hits_lost = int(d["P_hit"]) - int(s["P_hit"])
        default_lost += int(d.get("N_lost_planar", 0))
        pixels, diff = None, None
        if s.get("image") and d.get("image") and os.path.exists(s["image"]) \
                and os.path.exists(d["image"]):
            pixels, diff = pixel_diff(s["image"], d["image"])
        body.append([latex.escape(kr.TITLES[v]), latex.fmt_int(lost),
                     latex.fmt_int(s["P_hit"]), latex.fmt_int(d["P_hit"]),
                     latex.fmt_int(hits_lost),
                     latex.fmt_int(pixels) if pixels is not None
                     else latex.DASH,
                     latex.fmt_int(d.get("N_lost_planar", 0))])
        if pixels is not None and (worst is None or pixels > worst[2]):
            worst = (v, lost, pixels, s, d, diff)
    caption = ("Triangles lying in a split plane on a voxel world (every "
               "face on an integer plane). ``Lost'': references the strict "
               "partition of the seed-compatible mode sends to neither child "
               "(a triangle is missing from the image only if all its "
               "references are lost). ``Hits lost'': primary rays that hit "
               "in our default mode but miss in the seed mode (a ray through a hole "
               "may still hit a face behind it). ``Pixels differing'': "
               "pixels of the two images that are not identical.")
    ctx.write("planar.tex", latex.booktabs(header, body, align="lrrrrrr",
                                           caption=caption, label="tab:planar",
                                           size="footnotesize"))
    images = ""
    if worst:
        shutil.copy(worst[3]["image"], ctx.path("planar_seed.png"))
        shutil.copy(worst[4]["image"], ctx.path("planar_default.png"))
        mpimg.imsave(ctx.path("planar_diff.png"), worst[5])
        ctx.written += ["planar_seed.png", "planar_default.png",
                        "planar_diff.png"]
        images = ("\\begin{figure}[htbp]\\centering\n"
                  "\\includegraphics[width=0.32\\linewidth]{generated/planar_seed.png}\\hfill\n"
                  "\\includegraphics[width=0.32\\linewidth]{generated/planar_default.png}\\hfill\n"
                  "\\includegraphics[width=0.32\\linewidth]{generated/planar_diff.png}\n"
                  "\\caption{%s, %s: seed-compatible mode (left; in-plane "
                  "triangles lost), our default (middle), and the %s pixels "
                  "that differ, in red (right).}\n"
                  "\\label{fig:planar}\n\\end{figure}\n"
                  % (latex.escape(scene), latex.escape(kr.TITLES[worst[0]]),
                     latex.fmt_int(worst[2])))
    ctx.write("planar_images.tex", images)
    return {
        "PlanarScene": (latex.escape(scene), True),
        "PlanarTriangles": (latex.fmt_int(n_tri), False),
        "PlanarWorstVariant": (latex.escape(kr.TITLES[worst[0]]) if worst
                               else latex.DASH, True),
        "PlanarWorstLost": (latex.fmt_int(worst[1]) if worst else latex.DASH,
                            True),
        "PlanarWorstPixels": (latex.fmt_int(worst[2]) if worst
                              else latex.DASH, True),
        "PlanarDefaultLost": (latex.fmt_int(default_lost), False),
    }
