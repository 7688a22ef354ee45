"""The report's Figures 1 and 2: build and render time per scene for the nine
variants, on a log-scale axis (x: scene, y: seconds), one panel per group of
the report's tables (spatial median, binned SAH, clipping and pruning) with
the other six variants in grey behind, so that nine lines do not hide each
other; and the trade-off figure: each variant's build and render time
against the report's final variant's, per scene, as the median and
quartiles over the scenes. Output: fig1_build.pdf, fig2_render.pdf,
fig_tradeoff.pdf.
"""

import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

from analysis import figures  # noqa: E402
from analysis import kdtree_results as kr  # noqa: E402
from analysis import provenance  # noqa: E402

MARKERS = ["o", "s", "^"]
FINAL = "clipping-pruning"


def series(df, scenes, variant, column):
    """The variant's value per scene; NaN where missing or not positive
    (a log axis cannot show it)."""
    ys = []
    for scene in scenes:
        v = df[column].get((scene, variant)) if (scene, variant) in df.index else None
        ys.append(float(v) if v is not None and v == v and v > 0 else float("nan"))
    return ys


def time_figure(ctx, df, column, ylabel, filename):
    scenes = kr.scenes_in_order(df)
    with plt.rc_context(figures.STYLE):
        if not scenes:
            fig, ax = plt.subplots(figsize=(6.3, 2.0))
            ax.text(0.5, 0.5, "no kd-tree runs", ha="center", va="center",
                    transform=ax.transAxes)
            ax.set_axis_off()
        else:
            fig, axes = plt.subplots(len(kr.GROUPS), 1, sharex=True, sharey=True,
                                     figsize=(6.3, 2.0 * len(kr.GROUPS) + 0.4))
            xs = list(range(1, len(scenes) + 1))
            every = {v: series(df, scenes, v, column) for v in kr.VARIANTS}
            for ax, name, group in zip(axes, kr.GROUP_NAMES, kr.GROUPS):
                for v in kr.VARIANTS:
                    if v not in group:
                        ax.plot(xs, every[v], color="0.82", linewidth=0.6, zorder=1)
                for k, v in enumerate(group):
                    ax.plot(xs, every[v], marker=MARKERS[k % len(MARKERS)], markersize=3.2,
                            linewidth=0.9, label=kr.TITLES[v], zorder=2)
                ax.set_yscale("log")
                ax.grid(which="major", linewidth=0.4, alpha=0.5)
                # Above the panel, not over the lines; the group's name at
                # its right.
                ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3,
                          frameon=False, fontsize=7, borderaxespad=0.1)
                ax.set_title(name, loc="right", fontsize=7, pad=3)
                ax.set_ylabel(ylabel)
            axes[-1].set_xticks(xs)
            axes[-1].set_xticklabels(["%d" % x for x in xs])
            axes[-1].set_xlabel("scene (numbers of Table 2; names there)")
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def tradeoff(df):
    """{variant: (build ratios, render ratios)}: per scene, the variant's T_B
    and T_R over the report's final variant's on that scene."""
    out = {}
    for v in kr.VARIANTS + kr.BEYOND:
        b, r = [], []
        for scene in kr.scenes_in_order(df):
            if (scene, v) not in df.index or (scene, FINAL) not in df.index:
                continue
            mine, final = df.loc[(scene, v)], df.loc[(scene, FINAL)]
            for col, dest in (("T_B", b), ("T_R", r)):
                if kr.present(mine[col]) and kr.present(final[col]) and final[col] > 0:
                    dest.append(float(mine[col]) / float(final[col]))
        if b and r:
            out[v] = (b, r)
    return out


def quartiles(values):
    if len(values) < 2:
        return values[0], values[0], values[0]
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[0], statistics.median(values), q[2]


def tradeoff_figure(ctx, df, filename="fig_tradeoff.pdf"):
    data = tradeoff(df)
    with plt.rc_context(figures.STYLE):
        fig, ax = plt.subplots(figsize=(6.3, 4.4))
        colours = plt.get_cmap("tab20").colors
        for k, (v, (b, r)) in enumerate(data.items()):
            bl, bm, bh = quartiles(b)
            rl, rm, rh = quartiles(r)
            ax.errorbar([bm], [rm], xerr=[[bm - bl], [bh - bm]], yerr=[[rm - rl], [rh - rm]],
                        fmt="os^vDPX*hdp"[k % 11], markersize=4, capsize=2, linewidth=0.7,
                        color=colours[(2 * k) % 20 if k < 10 else 2 * (k - 10) + 1],
                        label=kr.TITLES[v] + (" (ours)" if v in kr.BEYOND else ""))
        if not data:
            ax.text(0.5, 0.5, "no kd-tree runs", ha="center", va="center", transform=ax.transAxes)
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(ticker.FormatStrFormatter("%g"))
            axis.set_minor_formatter(ticker.NullFormatter())
        ax.axhline(1, color="0.6", linewidth=0.5)
        ax.axvline(1, color="0.6", linewidth=0.5)
        ax.set_xlabel("build time $T_B$ / that of Clipping pruning (log)")
        ax.set_ylabel("render time $T_R$ / that of\nClipping pruning (log)")
        ax.grid(which="major", linewidth=0.4, alpha=0.5)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, frameon=False)
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "figures 1 and 2 (build and render time)")
    time_figure(ctx, df, "T_B", "build time $T_B$ (s, log)", "fig1_build.pdf")
    time_figure(ctx, df, "T_R", "render time $T_R$ (s, log)", "fig2_render.pdf")
    tradeoff_figure(ctx, df)
    return {}
