"""The report's Figures 1 and 2: build and render time per scene for the nine
variants, on a log-scale axis (x: scene, y: seconds). Output: fig1_build.pdf,
fig2_render.pdf.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import figures  # noqa: E402
from analysis import kdtree_results as kr  # noqa: E402
from analysis import provenance  # noqa: E402

MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*", "h"]


def time_figure(ctx, df, column, ylabel, filename):
    scenes = kr.scenes_in_order(df)
    with plt.rc_context(figures.STYLE):
        fig, ax = plt.subplots(figsize=(6.3, 3.4))
        if scenes:
            xs = list(range(1, len(scenes) + 1))
            for k, variant in enumerate(kr.VARIANTS):
                ys = []
                for scene in scenes:
                    v = df[column].get((scene, variant)) \
                        if (scene, variant) in df.index else None
                    ys.append(float(v) if v is not None and v == v and v > 0
                              else float("nan"))
                ax.plot(xs, ys, marker=MARKERS[k], markersize=3.5,
                        linewidth=0.8, label=kr.TITLES[variant])
            ax.set_yscale("log")
            ax.set_xticks(xs)
            ax.set_xticklabels(["%d" % x for x in xs])
            ax.set_xlabel("scene (numbers of Table~2; names there)"
                          .replace("~", " "))
            ax.set_ylabel(ylabel)
            ax.grid(which="major", linewidth=0.4, alpha=0.5)
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18),
                      ncol=3, frameon=False)
        else:
            ax.text(0.5, 0.5, "no kd-tree runs", ha="center", va="center",
                    transform=ax.transAxes)
            ax.set_axis_off()
        fig.tight_layout()
        fig.savefig(ctx.path(filename))
        plt.close(fig)
    ctx.written.append(filename)


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "figures 1 and 2 (build and render time)")
    time_figure(ctx, df, "T_B", "build time $T_B$ (s, log scale)",
                "fig1_build.pdf")
    time_figure(ctx, df, "T_R", "render time $T_R$ (s, log scale)",
                "fig2_render.pdf")
    return {}
