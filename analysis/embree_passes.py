"""Where the gap to Embree is: per pass, camera rays and shadow rays, single
rays and packets (issue 23).

Per scene with a run of our fastest tree (sah-packet, kdrt --fast_render with
Embree timed, one thread): kdrt times the kd-tree's answers replayed
(cc/render/replay_tracer.h: the renderer's own work on each pass, ray
generation, hit points, shadow-ray spawns, shading) in the same rounds as
the tracers, and subtracts it, round by round, from each tracer's pass time,
so that each ratio compares the two tracers' own work on that pass
(kdrt_record.h AddPassComparisons; record fast_render.passes). Each cell is
the median over the rounds of Embree's tracing time over ours in the same
round (above 1: ours is the faster), with the rounds' range: single rays,
Embree's rtcIntersect1 / rtcOccluded1 against the faster per round of our two
single-ray modes; packets, Embree's 16-ray packets (rtcIntersect16 with its
coherent flag, rtcOccluded16) against our fast mode's 4x4 packets. A run
made before kdrt recorded the passes gives dashes.

Output: embree_passes.tex and macros (per pass, the median over the scenes
of the paired medians, and how many scenes have one).
"""

import statistics

from analysis import embree
from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

TREE = "sah-packet"
# (record column prefix, macro name, header) per pass, in the table's order.
PASSES = [("camera_single", "CameraSingle", "camera"),
          ("shadow_single", "ShadowSingle", "shadow"),
          ("camera_packets", "CameraPackets", "camera"),
          ("shadow_packets", "ShadowPackets", "shadow")]
# The passes in words (macro EmbreePassWeakestClause).
WORDS = {"camera_single": "camera rays one at a time",
         "shadow_single": "shadow rays one at a time",
         "camera_packets": "camera rays in packets",
         "shadow_packets": "shadow rays in packets"}
MACROS = ["EmbreePass%s%s" % (name, what) for _, name, _ in PASSES
          for what in ("Median", "Scenes")] + ["EmbreePassWeakestClause"]


def rows(df):
    out = []
    for scene in kr.scenes_in_order(df):
        if (scene, TREE) not in df.index:
            continue
        r = df.loc[(scene, TREE)]
        if not kr.present(r["T_R_fast"]):
            continue
        row = {"scene": scene, "n_tri": int(r["n_tri"])}
        for prefix, _, _ in PASSES:
            row[prefix] = embree.ratio_cell(r, prefix + "_ratio")
        out.append(row)
    return out


def render(data):
    groups = [("", 2), ("Single rays", 2), ("Packets", 2)]
    header = ["Scene", "$N_{tri}$"] + [h for _, _, h in PASSES]
    body = [[latex.escape(r["scene"]), latex.fmt_int(r["n_tri"])] +
            [embree.fmt_cell(r[prefix]) for prefix, _, _ in PASSES] for r in data]
    if not body:
        body = [["\\emph{no runs of sah-packet in the fast mode}"] + [""] * (len(header) - 1)]
    caption = ("Where the gap to Embree~3 is, per pass: our tree "
               "\\texttt{sah-packet} against Embree (MEDIUM build, one thread) on "
               "the same rays, each pass's tracing time alone. In the same rounds "
               "as the tracers, the renderer runs on the kd-tree's answers "
               "replayed (its own work: ray generation, hit points, shadow-ray "
               "spawns, shading), and that is subtracted from each tracer's pass, "
               "round by round. A cell is the median over the rounds of Embree's "
               "tracing time over ours in the same round (above 1: ours is the "
               "faster), with the rounds' range. Single rays: "
               "\\texttt{rtcIntersect1} / \\texttt{rtcOccluded1} against the faster "
               "per round of our three single-ray modes; packets: Embree's 16-ray "
               "packets (\\texttt{rtcIntersect16} with its coherent flag, "
               "\\texttt{rtcOccluded16}) against our $4\\times 4$ packets, on the "
               "same blocks of pixels. A dash: the run recorded no passes.")
    return latex.booktabs(header, body, align="lrllll", caption=caption,
                          label="tab:embree-passes", size="footnotesize", groups=groups)


def pass_macros(data):
    """Per pass the median over the scenes of its paired medians and how many
    scenes have one; EmbreePassWeakestClause names the pass with the lowest
    median and gives it (or says that no run recorded the passes)."""
    out, medians = {}, {}
    for prefix, name, _ in PASSES:
        values = [r[prefix][0] for r in data if r[prefix] is not None]
        if values:
            medians[prefix] = statistics.median(values)
        out["EmbreePass%sMedian" % name] = (
            "%.2f" % medians[prefix] if values else latex.DASH, True)
        out["EmbreePass%sScenes" % name] = (str(len(values)), False)
    weakest = min(medians, key=medians.get) if medians else None
    out["EmbreePassWeakestClause"] = (
        "it is furthest behind on %s (%.2f of Embree's speed)" % (WORDS[weakest], medians[weakest])
        if weakest else "no run recorded its passes apart", False)
    return out


def generate(ctx):
    df = kr.frame(ctx.results(kr.KDTREE_FILE), ctx.manifest)
    provenance.check_frame(ctx, df, "the per-pass Embree table")
    data = rows(df)
    ctx.write("embree_passes.tex", render(data))
    return pass_macros(data)
