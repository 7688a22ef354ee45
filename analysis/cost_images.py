"""Cost images: where a tree is expensive. For each scene of matrix.json's
cost_image_scenes, one landscape figure of the inner nodes visited (N_TR) and
the triangles tested (N_IT) per primary ray and per shadow ray, pixel by
pixel, for the report's nine variants in the order of its columns and our
fastest tree, on one logarithmic colour scale per row (the kd-tree
literature's false-colour cost pictures, e.g. Wald's thesis, 2004, ch. 7).

Inputs: results/kdtree.jsonl (which runs, and their totals) and the cost
images kdrt writes on request (cc/render/cost_image.h) to
<results>/../costs/<scene>_<variant>.npy.gz, shape (height, width, kind,
{rays, inner visits, triangle tests}). An image is shown only when its sums
equal the totals of the record of the same run (rays, N_TR and N_IT per ray
kind): a file left by another run of other code is refused, and the caption
says how many were.

The in-plane study (experiments/run_planar.py) runs the nine variants in the
seed-compatible mode on its voxel world and writes their cost images to
<results>/../costs/planar/<scene>_<variant>_seed.npy.gz: drawn as a second
figure of that scene on the same colour scales.

Output: cost_images.tex, cost/<scene>.png, cost/<scene>_seed.png; macros
CostImageFigures (the references), CostImageScenes, CostImagesRefused.
"""

import gzip
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import ticker  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

from analysis import figures  # noqa: E402
from analysis import kdtree_results as kr  # noqa: E402
from analysis import latex  # noqa: E402
from analysis import planar  # noqa: E402  (PLANAR_FILE: the seed-mode runs)

FASTEST = "sah-packet"
SHOWN = kr.VARIANTS + [FASTEST]
KINDS = ("primary", "shadow")  # kind index 0 and 1 of the file
RAYS, INNER, TESTS = 0, 1, 2
ROWS = [("primary", INNER, "$N_{TR}$ per\nprimary ray"),
        ("primary", TESTS, "$N_{IT}$ per\nprimary ray"),
        ("shadow", INNER, "$N_{TR}$ per\nshadow ray"),
        ("shadow", TESTS, "$N_{IT}$ per\nshadow ray")]
CELL = 200  # pixels on the long side of each drawn image


def cost_scenes():
    return list(kr.load_matrix().get("cost_image_scenes", []))


def load(path):
    with gzip.open(path, "rb") as f:
        return np.load(f)


def matches_record(counts, rec):
    """Whether the image's sums are the record's totals (same run)."""
    trav = rec.get("traversal") or {}
    for k, kind in enumerate(KINDS):
        t = trav.get(kind)
        if t is None:
            return False
        rays = counts[:, :, k, RAYS].sum(dtype=np.uint64)
        if int(rays) != int(t["rays"]):
            return False
        for channel, field in ((INNER, "N_TR"), (TESTS, "N_IT")):
            total = float(counts[:, :, k, channel].sum(dtype=np.uint64))
            if abs(total - t[field] * t["rays"]) > 1e-6 * max(total, 1.0):
                return False
    return True


def crop_box(images):
    """(y0, y1, x0, x1): the pixels whose primary ray entered the tree (an
    inner node visited) in some variant, with a small margin; the whole
    frame when none did."""
    entered = np.zeros(next(iter(images.values())).shape[:2], dtype=bool)
    for counts in images.values():
        entered |= counts[:, :, 0, INNER] > 0
    ys, xs = np.nonzero(entered)
    h, w = entered.shape
    if ys.size == 0:
        return 0, h, 0, w
    pad = max(h, w) // 50
    return (max(0, ys.min() - pad), min(h, ys.max() + 1 + pad),
            max(0, xs.min() - pad), min(w, xs.max() + 1 + pad))


def mean_per_ray(counts, kind, channel):
    """The frame's mean (the record's N_TR or N_IT of that ray kind)."""
    k = KINDS.index(kind)
    rays = counts[:, :, k, RAYS].sum(dtype=np.uint64)
    return float(counts[:, :, k, channel].sum(dtype=np.uint64)) / rays if rays else None


def per_ray(counts, kind, channel):
    """Counts per ray of one kind, block-averaged to about CELL pixels (sum
    of counts over sum of rays per block); NaN where a block has no ray."""
    k = KINDS.index(kind)
    h, w = counts.shape[:2]
    step = max(1, -(-max(h, w) // CELL))
    hh, ww = h // step * step, w // step * step

    def blocks(a):
        a = a[:hh, :ww].astype(np.float64)
        return a.reshape(hh // step, step, ww // step, step).sum(axis=(1, 3))

    rays = blocks(counts[:, :, k, RAYS])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(rays > 0, blocks(counts[:, :, k, channel]) / rays, np.nan)


def row_norm(images):
    """One log scale for a row: from the 1st to the 99.5th percentile of its
    finite positive values over all variants (brighter values saturate; the
    colour bar says so)."""
    values = np.concatenate([a[np.isfinite(a) & (a > 0)] for a in images]
                            or [np.array([1.0])])
    if values.size == 0:
        values = np.array([1.0])
    lo = max(float(np.percentile(values, 1)), 0.5)
    hi = max(float(np.percentile(values, 99.5)), lo * 1.01)
    return LogNorm(vmin=lo, vmax=hi)


def short_title(variant):
    """The report's column title on two lines."""
    title = kr.TITLES[variant]
    if variant == FASTEST:
        return "SAH per packet\nof 4 (ours)"
    for prefix in ("Spatial median ", "Binning 8 ", "Clipping "):
        if title.startswith(prefix) and title != prefix.strip():
            return prefix.strip() + "\n" + title[len(prefix):]
    return title + "\n"


def draw(path, scene, images, like=None):
    """images: {variant: counts}; one row per ROWS entry that has rays.
    Returns (crop box, {row: colour scale}); `like`, such a pair from
    another figure of the scene, makes this one use the same."""
    variants = [v for v in SHOWN if v in images]
    y0, y1, x0, x1 = like[0] if like else crop_box(images)
    scales = {}
    means = {(v, r): mean_per_ray(images[v], r[0], r[1]) for v in variants for r in ROWS}
    images = {v: a[y0:y1, x0:x1] for v, a in images.items()}
    aspect = (y1 - y0) / max(1, x1 - x0)
    rows = [r for r in ROWS if any(
        images[v][:, :, KINDS.index(r[0]), RAYS].any() for v in variants)]
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("#d0d0d0")
    with plt.rc_context(figures.STYLE):
        fig, axes = plt.subplots(len(rows), len(variants) + 1, squeeze=False,
                                 figsize=(9.4, (0.84 * aspect + 0.16) * len(rows) + 0.35),
                                 gridspec_kw={"width_ratios": [1] * len(variants) + [0.08]})
        for r, (kind, channel, label) in enumerate(rows):
            data = [per_ray(images[v], kind, channel) for v in variants]
            norm = like[1].get((kind, channel)) if like else None
            norm = scales[(kind, channel)] = norm or row_norm(data)
            for c, (v, a) in enumerate(zip(variants, data)):
                ax = axes[r][c]
                shown = np.where(np.isfinite(a), np.maximum(a, norm.vmin), np.nan)
                im = ax.imshow(shown, cmap=cmap, norm=norm, interpolation="nearest")
                ax.set_xticks([])
                ax.set_yticks([])
                for side in ax.spines.values():
                    side.set_linewidth(0.4)
                mean = means[(v, (kind, channel, label))]
                ax.set_xlabel("mean %.1f" % mean if mean is not None else "", fontsize=6.5, labelpad=1)
                if r == 0:
                    ax.set_title(short_title(v), fontsize=7)
                if c == 0:
                    ax.set_ylabel(label, fontsize=7)
            bar = fig.colorbar(im, cax=axes[r][-1], extend="max")
            bar.ax.yaxis.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
            bar.ax.yaxis.set_major_formatter(ticker.FormatStrFormatter("%g"))
            bar.ax.yaxis.set_minor_locator(ticker.NullLocator())
            bar.ax.tick_params(labelsize=6.5)
        fig.subplots_adjust(left=0.05, right=0.95, top=1 - 0.3 / fig.get_figheight(),
                            bottom=0.16 / fig.get_figheight(), wspace=0.05, hspace=0.22)
        fig.savefig(path, dpi=200)
        plt.close(fig)
    return (y0, y1, x0, x1), scales


def caption(scene, n_variants, refused, with_fastest=True):
    return (
        "Cost images of %s: per pixel, the inner nodes visited ($N_{TR}$) and "
        "triangles tested ($N_{IT}$) by its primary ray and by its shadow ray "
        "(grey: no shadow ray, the primary ray missed), for %d variants in the "
        "order of the report's columns%s; one "
        "logarithmic colour scale per row, from its 1st to its 99.5th "
        "percentile (brighter saturates). Counted by kdrt's counting pass on "
        "the very rays of the timed render; each image's sums equal its "
        "record's $N_{TR}$ and $N_{IT}$.%s"
        % (latex.escape(scene), n_variants,
           ", the last our fastest tree" if with_fastest else "", _refused(refused)))


def seed_caption(scene, n_variants, refused):
    return (
        "Cost images of %s in the seed-compatible mode (the report's own rules, "
        "whose strict partition loses triangles lying in a split plane; "
        "Section~\\ref{sec:errata}), %d of the nine variants, on the colour "
        "scales of Figure~\\ref{fig:cost-%s}. From the runs of the in-plane "
        "study (Table~\\ref{tab:planar}), checked against their records like "
        "the others.%s" % (latex.escape(scene), n_variants, scene, _refused(refused)))


def _refused(n):
    return "" if not n else " %d image(s) did not match their record and are not shown." % n


def collect(records, path_of):
    """({variant: counts} of the images that match their record, how many
    did not): records is {variant: record}, path_of(variant) the file."""
    images, refused = {}, 0
    for v in SHOWN:
        rec, path = records.get(v), path_of(v)
        if rec is None or not os.path.exists(path):
            continue
        counts = load(path)
        if matches_record(counts, rec):
            images[v] = counts
        else:
            refused += 1
    return images, refused


def seed_records(ctx, scene):
    """{variant: the newest seed-mode record of the in-plane study}."""
    out = {}
    for rec in ctx.results(planar.PLANAR_FILE):
        if rec.get("ok") and rec.get("scene") == scene and rec.get("mode") == "seed":
            out[rec["preset"]] = rec
    return out


def landscape(name, text, label):
    return ("\\begin{landscape}\\begin{figure}[p]\\centering\n"
            "\\generatedfigure{%s}\n"
            "\\caption{%s}\\label{%s}\n\\end{figure}\\clearpage\\end{landscape}\n"
            % (name, text, label))


def generate(ctx):
    records = kr.latest(ctx.results(kr.KDTREE_FILE))
    costs_dir = os.path.join(os.path.dirname(os.path.abspath(ctx.results_dir)), "costs")
    wanted = cost_scenes()
    order = [s["name"] for s in ctx.manifest if s["name"] in wanted]
    os.makedirs(ctx.path("cost"), exist_ok=True)
    parts, shown, refused = [], [], 0
    for scene in order:
        images, n_refused = collect(
            {v: r for (sc, v), r in records.items() if sc == scene},
            lambda v: os.path.join(costs_dir, "%s_%s.npy.gz" % (scene, v)))
        refused += n_refused
        if not images:
            continue
        name = "cost/%s.png" % scene
        like = draw(ctx.path(name), scene, images)
        ctx.written.append(name)
        shown.append(scene)
        parts.append(landscape(name, caption(scene, len(images), n_refused, FASTEST in images), "fig:cost-%s" % scene))
        seed, n_refused = collect(
            seed_records(ctx, scene),
            lambda v: os.path.join(costs_dir, "planar", "%s_%s_seed.npy.gz" % (scene, v)))
        refused += n_refused
        if seed:
            name = "cost/%s_seed.png" % scene
            draw(ctx.path(name), scene, seed, like)
            ctx.written.append(name)
            parts.append(landscape(name, seed_caption(scene, len(seed), n_refused),
                                   "fig:cost-%s-seed" % scene))
    ctx.write("cost_images.tex", "".join(parts) if parts else
              "\\emph{No cost images (matrix.json's cost\\_image\\_scenes were "
              "not run, or their files did not match their records).}\n")
    refs = ["\\ref{fig:cost-%s}" % scene for scene in shown]
    figs = ("Figures~%s--%s" % (refs[0], refs[-1]) if len(refs) > 1
            else "Figure~%s" % refs[0] if refs else "none in this run")
    return {"CostImageFigures": (figs, True),
            "CostImageScenes": (str(len(shown)), False),
            "CostImagesRefused": (str(refused), False)}
