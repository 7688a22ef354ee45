"""The gallery: one rendered image per scene of the kd-tree runs (every
variant renders the same image, which kdrt's records show by one image hash
per scene), shrunk to thumbnails, as figures of up to 24 images.

Inputs: results/kdtree.jsonl (which scenes, in manifest order) and the PNGs
that experiments/run_matrix.py keeps in <results>/../images/<scene>_<variant>.png.
Output: gallery.tex, gallery/<scene>.png; macro GalleryImages.
"""

import os

from PIL import Image

from analysis import kdtree_results as kr
from analysis import latex

THUMB = 320          # pixels on the long side
PER_FIGURE = 24      # 6 x 4 per page
PREFERRED = "clipping-pruning"


def image_for(images_dir, scene, variants):
    """Path of one image of the scene, the report's final variant first."""
    for v in [PREFERRED] + [v for v in variants if v != PREFERRED]:
        path = os.path.join(images_dir, "%s_%s.png" % (scene, v))
        if os.path.exists(path):
            return path
    return None


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    images_dir = os.path.join(os.path.dirname(os.path.abspath(ctx.results_dir)),
                              "images")
    os.makedirs(ctx.path("gallery"), exist_ok=True)
    shown = []
    for scene in kr.scenes_in_order(df):
        path = image_for(images_dir, scene, kr.VARIANTS)
        if path is None:
            continue
        name = "gallery/%s.png" % scene
        with Image.open(path) as im:
            im.thumbnail((THUMB, THUMB))
            im.save(ctx.path(name))
        ctx.written.append(name)
        shown.append((scene, name))
    figures = []
    for start in range(0, len(shown), PER_FIGURE):
        part = shown[start:start + PER_FIGURE]
        cells = "\n".join(
            "\\begin{minipage}[t]{0.158\\linewidth}\\centering"
            "\\includegraphics[width=\\linewidth]{generated/%s}\\\\"
            "{\\tiny %s}\\end{minipage}%s"
            % (name, latex.escape(scene), "\\\\[2pt]" if (i + 1) % 6 == 0
               else "\\hfill")
            for i, (scene, name) in enumerate(part))
        label = "fig:gallery" if start == 0 else "fig:gallery%d" % start
        figures.append(
            "\\begin{figure}[p]\\centering\n%s\n\\caption{Gallery%s: every "
            "scene as rendered by our kd-tree (800$\\times$800, one point "
            "light, diffuse shading with shadows; the images of all nine "
            "variants are identical).}\n\\label{%s}\n\\end{figure}\n"
            % (cells, "" if start == 0 else " (continued)", label))
    ctx.write("gallery.tex", "".join(figures) if figures else
              "\\emph{No rendered images (run experiments/run\\_matrix.py).}\n")
    return {"GalleryImages": (str(len(shown)), False)}
