"""The Markdown tables of experiments/bench.py: build throughput and parallel
speed-up (build_summary), render throughput against Embree (render_summary),
issue 23's targets (targets_summary) and per pass (passes_summary); the
packet kernel's work and the structures' bytes are bench_structure.py's.

Issue 23's targets get a table of their own (targets_summary): per scene of
the render records, one thread, our fastest single-ray mode against Embree's
single rays (target 0.8) and our best mode against Embree's best mode (target
1.0), each per round (the faster mode of each side in that round), then the
median and range over the rounds; by render time (T_R) and, where the
records have render_bench's replays, by tracing time alone (each mode's T_R
less the replay of its mode in the same round: the renderer's own work,
shared by every tracer, taken out). passes_summary splits the tracing time
by pass (camera rays, shadow rays) for single rays and for packets, to show
where the gap is.

Numbers: T_B is the median of --repeats builds, and also the fastest, since
on a shared or virtual machine the slow runs carry other load; Mtri/s =
triangles / T_B. Render: kd/Embree = Embree's T_R / the kd-tree's T_R, medians
of interleaved rounds on the same rays (render_bench.cc).
"""
import statistics

# Issue 7's single-thread build targets, Mtri/s: binned SAH 3, clipping and
# pruning 1.5 (the presets beyond the report: cc/kdtree/config.h).
BUILD_TARGETS = {"binning-8-driving": 3.0, "binning-32": 3.0, "sah-packet-binned": 3.0,
                 "clipping-pruning": 1.5, "sah-packet-binned-cp": 1.5}


def build_summary(records):
    """Per (scene, preset): Mtri/s at each thread count and the speed-up."""
    rows = {}
    for r in records:
        key = (r["scene"], r["n_tri"], r["preset"])
        rows.setdefault(key, {})[r["threads"]] = r
    out = ["| scene | triangles | preset | 1 thread: T_B median (fastest), Mtri/s "
           "| 2 threads: T_B median (fastest), Mtri/s | speed-up (medians) "
           "| first build, untimed: 1 / 2 threads |",
           "|---|---|---|---|---|---|---|"]
    for (scene, n, preset), by_t in sorted(rows.items(), key=lambda kv: (kv[0][1], kv[0][2])):
        cells = []
        for t in (1, 2):
            r = by_t.get(t)
            cells.append("-" if r is None else "%.3f s (%.3f), %.2f (%.2f)" % (
                r["T_B"], min(r["T_B_runs"]), n / r["T_B"] / 1e6,
                n / min(r["T_B_runs"]) / 1e6))
        speed = ("%.2fx" % (by_t[1]["T_B"] / by_t[2]["T_B"])
                 if 1 in by_t and 2 in by_t else "-")
        # build_bench's --warmup builds (fresh pages), recorded apart.
        first = ["%.3f s" % r["T_B_warmup_runs"][0] if r and r.get("T_B_warmup_runs") else "-"
                 for r in (by_t.get(1), by_t.get(2))]
        out.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            scene, format(n, ","), preset, cells[0], cells[1], speed, " / ".join(first)))
    # Per preset: the 1-thread throughput against its target, and the speed-up.
    presets = sorted({p for (_, _, p) in rows})
    if presets:
        out.append("")
    for preset in presets:
        by = [by_t for (_, _, p), by_t in rows.items() if p == preset]
        mtri = [r[1]["n_tri"] / r[1]["T_B"] / 1e6 for r in by if 1 in r]
        ups = [r[1]["T_B"] / r[2]["T_B"] for r in by if 1 in r and 2 in r]
        line = "%s:" % preset
        if mtri:
            line += " 1 thread median %.2f Mtri/s (%.2f to %.2f)" % (
                statistics.median(mtri), min(mtri), max(mtri))
            if preset in BUILD_TARGETS:
                line += ", %d of %d at %.1f or more" % (
                    sum(m >= BUILD_TARGETS[preset] for m in mtri), len(mtri),
                    BUILD_TARGETS[preset])
        if ups:
            line += "; 2 threads %.2fx median (%.2f to %.2f), %d of %d at 1.7x or more" % (
                statistics.median(ups), min(ups), max(ups), sum(u >= 1.7 for u in ups),
                len(ups))
        out.append(line + ".")
    return "\n".join(out)


def render_summary(records):
    """Per (scene, preset): kd/Embree at 1 thread, the speed-up of 2 threads."""
    rows = {}
    for r in records:
        rows.setdefault((r["scene"], r["n_tri"], r["preset"]), {})[r["threads"]] = r
    out = ["| scene | triangles | preset | kd T_R, 1 thread | Embree T_R | kd/Embree "
           "| paired | packets: kd/Embree, paired "
           "| origin triangle untested: kd/Embree, paired "
           "| packets and origin untested: kd/Embree, kd/Embree packets, paired "
           "| kd 2-thread speed-up | Embree 2-thread speed-up | validation |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    ratios, paired_all, packet_all, origin_all = [], [], [], []
    both_all, both_packet_all = [], []
    for (scene, n, preset), by_t in sorted(rows.items(), key=lambda kv: (kv[0][1], kv[0][2])):
        one, two = by_t.get(1), by_t.get(2)
        if one is None or "kd" not in one["tracers"]:  # --variants without kd: no row
            continue
        kd, emb = one["tracers"]["kd"], one["tracers"].get("embree")
        ratio = emb["T_R_median"] / kd["T_R_median"] if emb else None
        # Per round, then the median (render_bench.cc): less exposed to slow
        # stretches of the machine than the ratio of the medians.
        paired = one.get("ratio_kd_over_embree", {}).get("kd", {}).get("paired")
        if paired is not None:
            paired_all.append(paired)
        # Packets of 4x4 pixels on both sides (kd_packet over embree_packet).
        packet = (one.get("ratio_kd_over_embree_packet") or {}).get("kd_packet", {}).get("paired")
        if packet is not None:
            packet_all.append(packet)
        # Shadow and AO rays leave their origin triangle untested (kd_origin).
        origin = one.get("ratio_kd_over_embree", {}).get("kd_origin", {}).get("paired")
        if origin is not None:
            origin_all.append(origin)
        # Both (kd_packet_origin), over Embree's single rays and its packets.
        both = one.get("ratio_kd_over_embree", {}).get("kd_packet_origin", {}).get("paired")
        both_packet = ((one.get("ratio_kd_over_embree_packet") or {})
                       .get("kd_packet_origin", {}).get("paired"))
        if both is not None:
            both_all.append(both)
        if both_packet is not None:
            both_packet_all.append(both_packet)
        if ratio is not None:
            ratios.append(ratio)

        def speed(name):
            if two is None or name not in two["tracers"]:
                return "-"
            return "%.2fx" % (one["tracers"][name]["T_R_median"] /
                              two["tracers"][name]["T_R_median"])

        v = one["validation"]
        d = v.get("embree_disagreements") or {}
        out.append("| %s | %s | %s | %.4f s | %s | %s | %s | %s | %s | %s | %s | %s | %d/%d "
                   "brute-force "
                   "mismatches, %s Embree disagreements |" % (
                       scene, format(n, ","), preset, kd["T_R_median"],
                       "%.4f s" % emb["T_R_median"] if emb else "-",
                       "%.2f" % ratio if ratio is not None else "-",
                       "%.2f" % paired if paired is not None else "-",
                       "%.2f" % packet if packet is not None else "-",
                       "%.2f" % origin if origin is not None else "-",
                       "%s, %s" % tuple("%.2f" % x if x is not None else "-"
                                        for x in (both, both_packet)),
                       speed("kd"), speed("embree"), v["brute_force_mismatches"],
                       v["brute_force_checked"], d.get("total", "-")))
    if ratios:
        out.append("")
        out.append("kd/Embree over %d rows: median %.2f, range %.2f to %.2f, %d at 0.7 or "
                   "more." % (len(ratios), statistics.median(ratios), min(ratios), max(ratios),
                              sum(r >= 0.7 for r in ratios)))
    if paired_all:
        out.append("Paired kd/Embree over %d rows: median %.2f, range %.2f to %.2f, %d at 0.7 "
                   "or more." % (len(paired_all), statistics.median(paired_all),
                                 min(paired_all), max(paired_all),
                                 sum(p >= 0.7 for p in paired_all)))
    if packet_all:
        out.append("Packets of 4x4 pixels, paired kd_packet/embree_packet over %d rows: median "
                   "%.2f, range %.2f to %.2f." % (len(packet_all), statistics.median(packet_all),
                                                  min(packet_all), max(packet_all)))
    if origin_all:
        out.append("Origin triangle untested (kd_origin), paired kd_origin/Embree over %d rows: "
                   "median %.2f, range %.2f to %.2f, %d at 0.7 or more." % (
                       len(origin_all), statistics.median(origin_all), min(origin_all),
                       max(origin_all), sum(p >= 0.7 for p in origin_all)))
    if both_all:
        line = ("Packets with the origin triangle untested (kd_packet_origin), paired "
                "kd_packet_origin/Embree over %d rows: median %.2f, range %.2f to %.2f, %d at "
                "0.7 or more" % (len(both_all), statistics.median(both_all), min(both_all),
                                 max(both_all), sum(p >= 0.7 for p in both_all)))
        if both_packet_all:
            line += "; over Embree's packets: median %.2f, range %.2f to %.2f, %d at 0.7 or more" % (
                statistics.median(both_packet_all), min(both_packet_all), max(both_packet_all),
                sum(p >= 0.7 for p in both_packet_all))
        out.append(line + ".")
    out.extend(coverage_lines(rows))
    return "\n".join(out)


# A scene whose camera rays hit fewer of its triangles than this share times
# those few, not the scene (render_check.h CameraCoverage: morse-trees and
# morse-buildings showed a sky box of 10 triangles until 2026-12-06); one
# whose shadow rays are nearly all occluded times a light that sees nothing
# (a light inside a closed mesh, say).
MIN_CAMERA_SHARE = 0.001
MAX_OCCLUDED_SHARE = 0.95


def coverage_lines(rows):
    """What the camera and the light see: the distinct triangles primary rays
    hit, as a share of each scene's triangles, and the share of shadow rays
    occluded (records from before 2026-12-06 have neither)."""
    share, occluded = {}, {}
    for (scene, n, _), by_t in rows.items():
        one = by_t.get(1)
        if one is not None and "camera_triangles" in one:
            share[scene] = one["camera_triangles"] / n
        if one is not None and "shadow_occluded" in one and one.get("shadow"):
            occluded[scene] = one["shadow_occluded"] / one["shadow"]
    out = []
    if share:
        few = sorted(s for s, x in share.items() if x < MIN_CAMERA_SHARE)
        least = min(share, key=share.get)
        out.append("Camera coverage: primary rays hit a median of %.1f %% of a scene's "
                   "triangles (fewest: %.2f %% on %s); under %.1f %%: %s." % (
                       100 * statistics.median(share.values()), 100 * share[least], least,
                       100 * MIN_CAMERA_SHARE, ", ".join(few) if few else "none"))
    if occluded:
        dark = sorted(s for s, x in occluded.items() if x > MAX_OCCLUDED_SHARE)
        most = max(occluded, key=occluded.get)
        out.append("Shadow rays occluded: median %.0f %% (most: %.0f %% on %s); over %.0f %%: "
                   "%s." % (100 * statistics.median(occluded.values()), 100 * occluded[most],
                            most, 100 * MAX_OCCLUDED_SHARE, ", ".join(dark) if dark else "none"))
    return out


# Our single-ray modes and Embree's (render_bench.cc tracer names). The best
# mode is the fastest of every tracer of ours ("kd...", packet modes and
# NAME@TARGET included; env: tracers are other trees, not modes).
# (kd_index and kd_mailbox were removed at 4c5d23d; kept here so that older
# records are still summarised as they were.) kd_bvh: the kd-tree's leaves
# under a BVH (cc/kdtree/leaf_bvh.h), single rays.
SINGLE_MODES = ("kd", "kd_index", "kd_mailbox", "kd_origin", "kd_bvh")
EMBREE_SINGLE = ("embree",)
EMBREE_ALL = ("embree", "embree_packet")
# The same Embree with RTC_SCENE_FLAG_ROBUST (render_bench --embree_robust).
EMBREE_ROBUST_SINGLE = ("embree_robust",)
EMBREE_ROBUST_ALL = ("embree_robust", "embree_robust_packet")
PACKET_MODES = ("kd_packet", "kd_packet_origin", "kd_bvh_packet", "embree_packet",
                "embree_robust_packet", "tri_bvh_packet")
# The baseline that is not a kd-tree: kd_bvh's kernels over a BVH of whole
# triangles (cc/kdtree/triangle_bvh.h), single rays and packets.
TRI_BVH_MODES = ("tri_bvh", "tri_bvh_packet")
# Issue 23's bars: single rays, best mode.
SINGLE_TARGET, BEST_TARGET = 0.8, 1.0


def key_runs(key="T_R_runs"):
    """A runs_of for per_round_ratio: a tracer's times under `key`, one per
    round in round order (T_R_runs: whole renders; primary_s_runs or
    secondary_s_runs: one pass)."""
    return lambda tracers, name: tracers.get(name, {}).get(key)


t_r_runs = key_runs("T_R_runs")  # a tracer's render times


def tracing_runs(key="T_R_runs"):
    """A runs_of for per_round_ratio: a tracer's times under `key` (T_R_runs:
    whole renders; primary_s_runs or secondary_s_runs: one pass) less the
    replay of its mode under the same key, round by round (render_bench
    --replay: the renderer's own work), i.e. its tracing time alone; None
    without them (--replay=false, or records from before the per-round pass
    times)."""
    def runs_of(tracers, name):
        mode = "replay_packet" if name.split("@")[0] in PACKET_MODES else "replay"
        runs, replay = tracers.get(name, {}).get(key), tracers.get(mode, {}).get(key)
        if not runs or not replay:
            return None
        return [t - r for t, r in zip(runs, replay)]
    return runs_of


def per_round_ratio(tracers, theirs, ours, runs_of=t_r_runs):
    """Per round, the fastest of Embree's modes `theirs` over the fastest of
    our modes `ours` (runs_of: one time per round, in round order), as
    (median, min, max) over the rounds; None when a side has no mode. A time
    that is not positive (a tracing time within the noise of its replay) is
    left out, and so is a round with no positive time on one side."""
    emb = [x for x in (runs_of(tracers, n) for n in theirs) if x]
    kd = [x for x in (runs_of(tracers, n) for n in ours) if x]
    if not emb or not kd:
        return None
    rounds = min(len(x) for x in emb + kd)
    r = []
    for i in range(rounds):
        a = [e[i] for e in emb if e[i] > 0]
        b = [k[i] for k in kd if k[i] > 0]
        if a and b:
            r.append(min(a) / min(b))
    if not r:
        return None
    return statistics.median(r), min(r), max(r)


def median_range(values):
    """A table cell: the median [lowest..highest] of `values`, "-" for none."""
    if not values:
        return "-"
    return "%.2f [%.2f..%.2f]" % (statistics.median(values), min(values), max(values))


def one_thread_by_size(records):
    """The one-thread records, by triangle count, scene and preset."""
    one_thread = [r for r in records if r.get("threads") == 1]
    return sorted(one_thread, key=lambda r: (r["n_tri"], r["scene"], r["preset"]))


def targets_summary(records, robust=False):
    """Issue 23's targets per scene (one thread): single/single and
    best/best, paired per round, by render time and, where the record has the
    replays, by tracing time alone. With `robust`, against Embree built with
    RTC_SCENE_FLAG_ROBUST instead (rows without it are left out), with the
    rays it answers wrongly (render_bench's validation: its answer differs
    from ours and the exact check, compare.h, sides with ours) and how many of
    the rays it disagrees on start within rounding of a reported triangle's
    plane (compare.h's at_origin: a ray spawned from a surface)."""
    embree_single = EMBREE_ROBUST_SINGLE if robust else EMBREE_SINGLE
    embree_all = EMBREE_ROBUST_ALL if robust else EMBREE_ALL
    out = ["| scene | triangles | preset | single rays / Embree's single rays "
           "| best mode / Embree's best mode | tracing alone: single / single "
           "| tracing alone: best / best |%s" % (" Embree wrong: primary, shadow "
                                                  "(disagreeing at the origin) |"
                                                  if robust else ""),
           "|---|---|---|---|---|---|---|%s" % ("---|" if robust else "")]
    columns = [[], [], [], []]
    for r in one_thread_by_size(records):
        t = r["tracers"]
        if robust and embree_single[0] not in t:
            continue
        # Not the tracers that trace each query twice (render_bench --twice).
        ours = [n for n in t if n.startswith("kd") and not n.endswith("_twice")]
        single = [n for n in ours if n in SINGLE_MODES]
        values = [per_round_ratio(t, embree_single, single),
                  per_round_ratio(t, embree_all, ours),
                  per_round_ratio(t, embree_single, single, tracing_runs()),
                  per_round_ratio(t, embree_all, ours, tracing_runs())]
        cells = []
        for k, value in enumerate(values):
            if value is None:
                cells.append("-")
                continue
            columns[k].append(value[0])
            bar = SINGLE_TARGET if k % 2 == 0 else BEST_TARGET
            cells.append("%.2f [%.2f..%.2f]%s" % (value + (" (met)" if value[0] >= bar else "",)))
        if robust:
            d = r.get("validation", {}).get("embree_robust_disagreements") or {}
            cells.append("%s, %s (%s)" % (
                tuple(format(d.get(k, {}).get("other_wrong", 0), ",")
                      for k in ("primary", "shadow")) + (format(d.get("at_origin", 0), ","),)))
        out.append("| %s | %s | %s | %s |" % (r["scene"], format(r["n_tri"], ","), r["preset"],
                                              " | ".join(cells)))
    names = ("Single rays against Embree's single rays", "Best mode against Embree's best mode",
             "Tracing alone, single rays against Embree's single rays",
             "Tracing alone, best mode against Embree's best mode")
    for k, (name, values) in enumerate(zip(names, columns)):
        bar = SINGLE_TARGET if k % 2 == 0 else BEST_TARGET
        if values:
            out.append("")
            out.append("%s over %d rows: median %.2f, range %.2f to %.2f, %d at %.1f or "
                       "more." % (name, len(values), statistics.median(values), min(values),
                                  max(values), sum(v >= bar for v in values), bar))
    return "\n".join(out)


def passes_summary(records):
    """Where issue 23's gap is, per pass (one thread): each pass's tracing
    time alone (the pass less its mode's replay in the same round), Embree's
    over ours, paired per round as in targets_summary: camera rays and
    secondary rays (shadow rays, and AO rays where a view asks for them),
    single rays (the faster of our single-ray modes against rtcIntersect1
    / rtcOccluded1) and packets (the faster of our packet modes against
    Embree's 16-ray packets). Below 1: that pass traces slower than Embree's."""
    out = ["| scene | triangles | primary, single | shadow, single | primary, packets "
           "| shadow, packets |", "|---|---|---|---|---|---|"]
    passes = [("primary_s_runs", False), ("secondary_s_runs", False),
              ("primary_s_runs", True), ("secondary_s_runs", True)]
    columns = [[] for _ in passes]
    for r in one_thread_by_size(records):
        t = r["tracers"]
        ours_single = [n for n in t if n in SINGLE_MODES]
        ours_packets = [n for n in t if n.startswith("kd") and n.split("@")[0] in PACKET_MODES]
        cells = []
        for k, (key, packets) in enumerate(passes):
            value = per_round_ratio(t, ("embree_packet",) if packets else EMBREE_SINGLE,
                                    ours_packets if packets else ours_single,
                                    tracing_runs(key))
            if value is None:
                cells.append("-")
                continue
            columns[k].append(value[0])
            cells.append("%.2f [%.2f..%.2f]" % value)
        if any(c != "-" for c in cells):
            out.append("| %s | %s | %s |" % (r["scene"], format(r["n_tri"], ","), " | ".join(cells)))
    for name, values in zip(("Primary rays, single", "Shadow rays, single", "Primary rays, packets",
                             "Shadow rays, packets"), columns):
        if values:
            out.append("")
            out.append("%s, tracing alone, Embree's over ours over %d rows: median %.2f, range "
                       "%.2f to %.2f." % (name, len(values), statistics.median(values),
                                          min(values), max(values)))
    return "\n".join(out)
