"""The provenance of the report's numbers, for its first page: macros made
from the kd-tree runs' records themselves (results/kdtree.jsonl, the newest
successful record of each scene and variant, as the tables use them), not
from machine.json (analysis/machine.py describes the machine the pipeline
started on).

When the tables were allowed to mix provenances (make_all
--allow_mixed_provenance or --allow_mixed_cpus), each macro lists every
value, separated by semicolons.
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance as pv

# Results files of kdrt records besides kdtree.jsonl (experiments/*.py).
STUDIES = [("accuracy.jsonl", "accuracy study"),
           ("planar.jsonl", "planar study")]
MACROS = ["ProvCommit", "ProvCommitFull", "ProvSourceTree", "ProvDirty",
          "ProvBuild", "ProvCPU", "ProvCores", "ProvTiming", "ProvRecords",
          "ProvStudies"]
UNKNOWN_BESIDE = ("timed steps with an unknown number of other timed "
                  "processes beside them")


def build_text(prov):
    """Compilation mode, flags, compiler and ISA in words (LaTeX)."""
    isa = [name for key, name in (("avx2", "AVX2"), ("avx512f", "AVX-512F"),
                                  ("fma", "FMA")) if prov.get(key)]
    flags = ["optimised" if prov.get("optimized") else "not optimised",
             "asserts off" if prov.get("ndebug") else "asserts on"]
    return "\\texttt{%s} (%s), compiler %s, %s" % (
        latex.escape(prov.get("compilation_mode") or "unknown"),
        ", ".join(flags), latex.escape(prov.get("compiler") or "unknown"),
        "+".join(isa) if isa else "no AVX2 or FMA")


def _alone(provs):
    if not provs or any(p is None for p in provs):
        return UNKNOWN_BESIDE
    if all(p.get("timing_lock") and p.get("timed_beside") == 0 for p in provs):
        return "timed steps alone under a machine-wide lock"
    beside = [p.get("timed_beside") for p in provs]
    if None in beside:
        return UNKNOWN_BESIDE
    return "timed steps with up to %d other timed processes beside them" % max(beside)


def _rounds(records):
    """What the timed rounds were: paired with Embree's in every run, in
    some, or in none."""
    paired = sum(1 for r in records if isinstance(r.get("embree"), dict)
                 and r["embree"].get("paired_ratio_runs"))
    if paired == len(records):
        return "paired rounds (kd-tree and Embree alternating)"
    if paired:
        return ("timed rounds (alternating with Embree's in the %d run%s "
                "that ran it)" % (paired, "" if paired == 1 else "s"))
    return "timed rounds"


def timing_text(records):
    """How the timed steps were taken: alone or not, the warm-up, rounds."""
    parts = [_alone([pv.of(r) for r in records])]
    warm = sum(1 for r in records if kr.present(r.get("T_R_warmup")))
    if warm == len(records) and warm:
        parts.append("1 untimed warm-up per tracer excluded")
    elif warm:
        parts.append("1 untimed warm-up excluded in %d of %d runs"
                     % (warm, len(records)))
    rounds = [len(r["T_R_runs"]) for r in records
              if isinstance(r.get("T_R_runs"), list)]
    if rounds:
        lo, hi = min(rounds), max(rounds)
        kind = _rounds(records)
        parts.append("%d%s %s" % (lo, "" if lo == hi else "--%d" % hi,
                                  kind.replace("rounds", "round", 1)
                                  if hi == 1 else kind))
    quiet = _quiet_cpu(records)
    if quiet:
        parts.append(quiet)
    return ", ".join(parts)


def _quiet_cpu(records):
    """The single-thread renders pinned to the quieter CPU (kdrt since
    2026-12-06, cc/base/quiet_cpu.h) and the probe of the CPU they ran on:
    how busy the machine was. '' when no record has it."""
    probes = [ms for ms in map(pv.cpu_probe, records) if ms is not None]
    if not probes:
        return ""
    return ("renders on the quieter CPU in %d of %d runs (its probe %.1f ms median, %.1f to "
            "%.1f: higher is a busier machine)" % (len(probes), len(records),
                                                   statistics.median(probes), min(probes),
                                                   max(probes)))


def _values(grouped, get):
    """Every distinct get(provenance) over the groups, "; "-separated
    ("unknown" for a record without provenance)."""
    values = []
    for prov, _ in grouped:
        value = get(prov) if prov is not None else "unknown"
        if value not in values:
            values.append(value)
    return "; ".join(str(v) for v in values)


def study_text(ctx, known):
    """Whether the other studies of kdrt records share the runs' code."""
    same, other = [], []
    for name, title in STUDIES:
        recs = [r for r in ctx.results(name) if r.get("ok")]
        if not recs:
            continue
        if {pv.code_key(pv.of(r)) for r in recs} <= known:
            same.append(title)
        else:
            other.append("The %s comes from other code: %s." % (
                title, latex.escape("; ".join(
                    pv.short(p) for p, _ in pv.groups(recs, pv.code_key)))))
    text = ["The %s share%s it." % (" and the ".join(same),
                                    "" if len(same) > 1 else "s")] if same else []
    return " ".join(text + other)


def generate(ctx):
    records = list(kr.latest(ctx.results(kr.KDTREE_FILE)).values())
    if not records:
        macros = {m: ("unknown", False) for m in MACROS}
        macros.update(ProvRecords=("0", False), ProvStudies=("", False),
                      ProvDirty=("", False),
                      ProvTiming=("no kd-tree runs", False))
        return macros
    grouped = pv.groups(records, lambda p: (pv.code_key(p), pv.cpu_name(p)))
    dirty = any(p is not None and p.get("dirty") for p, _ in grouped)
    return {
        "ProvCommit": (_values(grouped, lambda p: (p.get("commit") or "unknown")[:12]), False),
        "ProvCommitFull": (_values(grouped, lambda p: p.get("commit") or "unknown"), False),
        "ProvSourceTree": (_values(grouped, lambda p: (p.get("source_tree") or "unknown")[:12]), False),
        "ProvDirty": (" (with uncommitted changes)" if dirty else "", False),
        "ProvBuild": (_values(grouped, build_text), True),
        "ProvCPU": (_values(grouped, lambda p: pv.cpu_name(p) or "unknown CPU"), False),
        "ProvCores": (_values(grouped, lambda p: p.get("cores") or "unknown"), False),
        "ProvTiming": (timing_text(records), False),
        "ProvRecords": (latex.fmt_int(len(records)), False),
        "ProvStudies": (study_text(ctx, {pv.code_key(p) for p, _ in grouped}), True),
    }
