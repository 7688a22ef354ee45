"""The second trace of every ray and packet, right after the first
(render_bench --twice, cc/bench/twice_tracer.h): per scene and pass, how much
of each tracer's tracing time is first touches (caches and branch
predictors warm from the first trace), and Embree's speed over ours on the
first trace and on the warm second one. If the two ratios agree, the gap is
in the work that stays when the caches and predictors are warm; if the warm
one is nearer 1, it is in the first touches (memory, prediction).

Per round: the first trace's time is the tracer's pass less its mode's replay
(the renderer's own work, as bench_tables.tracing_runs), the second trace's
is NAME_twice's pass less NAME's. Each ratio is paired per round, then the
median [lowest..highest] over the rounds; a round where one of the four
times is not positive (within the noise of the subtraction) is left out."""
import statistics

import bench_tables

# Per kind of tracing: our mode and Embree's.
MODES = (("single", "kd_origin", "embree"), ("packets", "kd_packet_origin", "embree_packet"))
PASSES = (("primary_s_runs", "camera"), ("secondary_s_runs", "shadow"))


def first_and_second(tracers, name, key):
    """Per round, (first trace, second trace) of tracer `name` on pass `key`:
    the first is its tracing time alone (bench_tables.tracing_runs: the pass
    less its mode's replay); None without NAME_twice or the replay."""
    first = bench_tables.tracing_runs(key)(tracers, name)
    once, twice = (tracers.get(n, {}).get(key) for n in (name, name + "_twice"))
    if not first or not once or not twice:
        return None
    return [(f, t - o) for f, o, t in zip(first, once, twice)]


def warm_summary(records):
    """One row per one-thread record, pass and kind of tracing with both
    tracers traced twice (see the module's text)."""
    cell = bench_tables.median_range
    out = ["| scene | triangles | rays | ours: second / first trace "
           "| Embree: second / first trace | Embree's over ours: first trace "
           "| Embree's over ours: second trace |", "|---|---|---|---|---|---|---|"]
    first_all, second_all = {}, {}
    one_thread = sorted((r for r in records if r.get("threads") == 1),
                        key=lambda r: (r["n_tri"], r["scene"]))
    for r in one_thread:
        t = r["tracers"]
        for kind, ours, theirs in MODES:
            for key, pass_name in PASSES:
                a = first_and_second(t, ours, key)
                b = first_and_second(t, theirs, key)
                if a is None or b is None:
                    continue
                rounds = [(o, e) for o, e in zip(a, b) if min(o + e) > 0]
                if not rounds:
                    continue
                label = "%s, %s" % (pass_name, kind)
                first = [e[0] / o[0] for o, e in rounds]
                second = [e[1] / o[1] for o, e in rounds]
                first_all.setdefault(label, []).append(statistics.median(first))
                second_all.setdefault(label, []).append(statistics.median(second))
                out.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                    r["scene"], format(r["n_tri"], ","), label,
                    cell([o[1] / o[0] for o, _ in rounds]),
                    cell([e[1] / e[0] for _, e in rounds]), cell(first), cell(second)))
    for label, values in first_all.items():
        out.append("")
        out.append("%s over %d rows, Embree's over ours: first trace median %.2f (%.2f to %.2f), "
                   "second trace median %.2f (%.2f to %.2f)." % (
                       label.capitalize(), len(values), statistics.median(values), min(values),
                       max(values), statistics.median(second_all[label]),
                       min(second_all[label]), max(second_all[label])))
    return "\n".join(out)
