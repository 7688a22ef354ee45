"""Figures (matplotlib, Agg backend, PDF output for the report).

`log_bars` is the shared helper for the later build/render-time figures
(log-scale value per scene, one bar series per configuration). For now one
figure uses it: scene sizes, ours against the report's.
"""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be set first)

from analysis import table1  # noqa: E402

# Same look for every figure in the report.
STYLE = {
    "font.size": 8,
    "axes.titlesize": 9,
    "legend.fontsize": 7,
    "figure.dpi": 150,
    "pdf.fonttype": 42,  # embed TrueType, not Type 3
}


def log_bars(ax, labels, series, xlabel):
    """Horizontal grouped bars on a log x axis.

    labels : one label per group (scene), top to bottom.
    series : list of (name, values); a value of None/<=0 leaves a gap
             (a log axis cannot show it).
    """
    n = max(len(series), 1)
    height = 0.8 / n
    positions = list(range(len(labels)))
    for k, (name, values) in enumerate(series):
        if len(values) != len(labels):
            raise ValueError("series %r has %d values for %d labels"
                             % (name, len(values), len(labels)))
        ys = [p - 0.4 + height * (k + 0.5) for p in positions]
        pts = [(y, v) for y, v in zip(ys, values) if v is not None and v > 0]
        if pts:
            ax.barh([y for y, _ in pts], [v for _, v in pts], height=height,
                    label=name)
    ax.set_xscale("log")
    positive = [v for _, values in series for v in values
                if v is not None and v > 0]
    if positive:
        # Bars grow from the left edge: start a decade below the smallest
        # value so even the smallest bar is visibly long.
        ax.set_xlim(left=10 ** math.floor(math.log10(min(positive))))
    ax.set_yticks(positions)
    ax.set_yticklabels(labels)
    ax.invert_yaxis()
    ax.set_xlabel(xlabel)
    ax.grid(axis="x", which="major", linewidth=0.4, alpha=0.5)
    if len(series) > 1:
        ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2,
                  frameon=False)


def scene_sizes(ctx, filename="fig_scene_sizes.pdf"):
    """Triangles per loaded scene; for stand-ins also the report's N_tri."""
    seed = ctx.seed_table1
    rows = [r for r in table1.build_rows(ctx.manifest,
                                         ctx.results(table1.SCENES_FILE))
            if r["ok"]]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.5, 0.5 + 0.22 * max(len(rows), 3)))
        if rows:
            labels, ours, theirs = [], [], []
            for r in rows:
                rs = r["scene"].get("report_scene")
                rs = int(rs) if rs not in (None, "") else None
                labels.append("%s %s" % (r["number"], r["name"]) +
                              ("  (for %d)" % rs if rs else ""))
                ours.append(r["n_tri"])
                theirs.append(int(seed.loc[rs, "n_tri"])
                              if rs and rs in seed.index else None)
            series = [("this reproduction", ours)]
            if any(v is not None for v in theirs):
                series.append(("the report (scene stood in for)", theirs))
            log_bars(ax, labels, series, "triangles (log scale)")
        else:
            ax.text(0.5, 0.5, "no scene loaded", ha="center", va="center",
                    transform=ax.transAxes)
            ax.set_axis_off()
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def generate(ctx):
    scene_sizes(ctx)
    return {}
