"""render_bench's records of one scene from several processes, pooled
(experiments/bench.py --processes N).

On this project's 2-core VMs the same paired ratio moves between
render_bench processes by up to about 0.06 of render time (and 0.1 on a
pass), more than between the rounds of one process: each process builds its
trees and Embree's anew, in other memory. So one process's verdict on a bar
such as issue 23's 0.8 can fall either way. Pooling the rounds of several
processes, each round still pairing the tracers it timed together, puts that
spread into the rounds' range and the median over them.

merge_processes(records) groups the render records by bench, scene, preset,
thread count and provenance (commit and source tree: never pools different
code) and returns one record per group, in first-seen order: each tracer's
per-round lists (every field ending in _runs) concatenated in process order,
its medians and minimum recomputed from them, the ratios to Embree
(ratio_kd_over_embree, ratio_kd_over_embree_packet) recomputed from the
pooled rounds, the validation's mismatch counts summed, the ray classes'
per-round times (ray_classes, render_bench --classes) concatenated per class
and tracer, "processes" the number of records pooled. Derived fields it
does not recompute (first_over_this_paired, trace_s_median,
mrays_per_s_median, ratio_trace_only, the ray classes' medians and ratios,
which experiments/bench_classes.py computes from the runs) are dropped from
pooled records rather than left stale; so are ray classes that not every
record of the group has.
A group of one record is returned as it is, with "processes": 1."""
import copy
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from analysis import provenance  # noqa: E402  (cpu_probe: the record's CPU probe)

DROPPED = ("first_over_this_paired", "trace_s_median", "mrays_per_s_median")


def _key(r):
    p = r.get("provenance") or {}
    return (r.get("bench"), r["scene"], r.get("preset"), r.get("threads"), p.get("commit"),
            p.get("source_tree"))


def _ratios(tracers, names, embree):
    """Per kd-tree variant, Embree's (`embree`) T_R over its own: of the
    medians, of the minima, and paired per round then the median."""
    e = tracers.get(embree, {}).get("T_R_runs")
    if not e:
        return {}
    out = {}
    for n in names:
        k = tracers[n]["T_R_runs"]
        out[n] = {"median": statistics.median(e) / statistics.median(k),
                  "min": min(e) / min(k),
                  "paired": statistics.median([a / b for a, b in zip(e, k)])}
    return out


def _pool_classes(group):
    """The ray classes' ns_runs pooled per class and tracer; None unless
    every record has them."""
    tables = [(r.get("ray_classes") or {}).get("classes") for r in group]
    if not all(tables):
        return None
    pooled = {}
    for name, c in tables[0].items():
        if not all(name in t for t in tables):
            continue
        tracers = [n for n in c["ns_runs"] if all(n in t[name]["ns_runs"] for t in tables)]
        pooled[name] = {"rays": c["rays"],
                        "ns_runs": {n: [x for t in tables for x in t[name]["ns_runs"][n]]
                                    for n in tracers}}
    return {"rounds": sum(r["ray_classes"].get("rounds", 0) for r in group), "classes": pooled}


def _pool(group):
    merged = copy.deepcopy(group[0])
    names = [n for n in merged["tracers"] if all(n in r["tracers"] for r in group)]
    merged["tracers"] = {}
    for n in names:
        t = {k: v for k, v in group[0]["tracers"][n].items() if k not in DROPPED}
        for k in t:
            if k.endswith("_runs"):
                t[k] = [x for r in group for x in r["tracers"][n][k]]
        t["T_R_median"] = statistics.median(t["T_R_runs"])
        t["T_R_min"] = min(t["T_R_runs"])
        for k in ("primary_s", "secondary_s"):
            if k + "_runs" in t:
                t[k + "_median"] = statistics.median(t[k + "_runs"])
        merged["tracers"][n] = t
    kd = [n for n in names if n.startswith("kd")]
    merged["ratio_kd_over_embree"] = _ratios(merged["tracers"], kd, "embree")
    merged["ratio_kd_over_embree_packet"] = _ratios(merged["tracers"], kd, "embree_packet")
    merged.pop("ratio_trace_only", None)
    v = merged.get("validation", {})
    for k in ("brute_force_checked", "brute_force_mismatches"):
        if k in v:
            v[k] = sum(r["validation"][k] for r in group)
    if "variants_vs_kd_mismatches" in v:
        v["variants_vs_kd_mismatches"] = {
            n: sum(r["validation"]["variants_vs_kd_mismatches"].get(n, 0) for r in group)
            for n in v["variants_vs_kd_mismatches"]}
    if "ray_classes" in merged:
        merged["ray_classes"] = _pool_classes(group)
    merged["repeats"] = sum(r.get("repeats", 0) for r in group)
    merged["processes"] = len(group)
    return merged


def merge_processes(records):
    groups = {}
    for r in records:
        groups.setdefault(_key(r), []).append(r)
    out = []
    for group in groups.values():
        out.append(dict(group[0], processes=1) if len(group) == 1 else _pool(group))
    return out


def processes_line(records):
    """A sentence on how many processes the rows pool; '' for one each."""
    counts = sorted({r.get("processes", 1) for r in records})
    if not counts or counts == [1]:
        return ""
    n = str(counts[0]) if len(counts) == 1 else "%d to %d" % (counts[0], counts[-1])
    return ("Each row pools the rounds of %s render_bench processes "
            "(experiments/bench_merge.py)." % n)


# A record whose rounds ran on a CPU probing this much slower than the
# quickest probe of the summary's records ran in a slow state of the machine
# (cc/base/quiet_cpu.h): on 2026-12-06 the probe read 2.7 ms quiet and 3.5 to
# 5.1 ms when the renderer's own camera pass ran 1.7 times slower.
SLOW_PROBE = 1.25


def probe_line(records):
    """A sentence on the machine's state in the records' rounds: the probe of
    the CPU each one-thread record's rounds ran on (timing.cpu_probe_ms at
    timing.cpu, render_bench since f8dfb55), and how many ran slow; '' when no
    record has it. Give it the records before merge_processes, which keeps
    the first process's timing only."""
    probes = [provenance.cpu_probe(r) for r in records if r.get("threads") == 1]
    probes = [ms for ms in probes if ms is not None]
    if not probes:
        return ""
    fastest = min(probes)
    slow = sum(ms > SLOW_PROBE * fastest for ms in probes)
    return ("The CPU probe of the rounds (cc/base/quiet_cpu.h): median %.2f ms, %.2f to %.2f; "
            "%d of %d one-thread records above %.2f times the quickest, in a slow state of the "
            "machine." % (statistics.median(probes), fastest, max(probes), slow, len(probes),
                          SLOW_PROBE))
