"""Where a record's numbers came from, and the checks that keep one table to
one answer (issue 22).

Every record of the C++ tools carries one object "provenance" (cc/base/
provenance.h): the commit, whether the checkout was dirty, the id of the
source tree that built the tool (equal to the commit's tree when clean: the
code's identity), the compilation mode and flags, the CPU and its cores, and
whether the timed steps ran alone under the machine-wide timing lock. A record
without it is of unknown provenance, which differs from every known one.

Two records may share a table only when their code (source tree and
compilation mode) and their CPU (cpu_name: the model name with the family,
model, stepping and caches where recorded) are the same, and a table may show
timings only from binaries built for timing (timing_build). The checks raise
errors that name the provenances and the make_all flag that overrides them:
--allow_mixed_provenance, --allow_mixed_cpus, --allow_unoptimized_timings.

analysis/provenance_macros.py states on the report's first page the
provenance of its numbers.
"""


class ProvenanceError(ValueError):
    """Records of different provenance would share one table or figure."""


class MixedCpuError(ProvenanceError):
    """Timings measured on different CPUs (cpu_name) would share one table."""


class UnoptimizedTimingError(ProvenanceError):
    """A table would show timings from a binary not built for timing."""


def of(record):
    """The record's provenance object, or None (unknown: an old record)."""
    prov = record.get("provenance") if isinstance(record, dict) else None
    return prov if isinstance(prov, dict) else None


def cpu_probe(record):
    """The probe (ms) of the CPU a record's single-thread timed rounds ran on
    (kdrt and render_bench since 2026-12-06, "timing": cpu, cpu_probe_ms;
    cc/base/quiet_cpu.h): higher is a busier machine. None without it."""
    timing = record.get("timing") if isinstance(record, dict) else None
    if not isinstance(timing, dict):
        return None
    return (timing.get("cpu_probe_ms") or {}).get(str(timing.get("cpu")))


def code_key(prov):
    """What must be equal for two records' numbers to come from one code:
    the source tree (or, without it, the commit and dirtiness) and the
    compilation mode. None for an unknown provenance."""
    if prov is None:
        return None
    code = (prov.get("source_tree"),) if prov.get("source_tree") else \
        ("commit", prov.get("commit"), bool(prov.get("dirty")))
    return code + (prov.get("compilation_mode"),)


def cpu_name(prov):
    """The CPU a provenance names: its model name, with the family, model,
    stepping and cache sizes (cpu_id, cpu_caches; records since 32f81fd)
    in parentheses when known (the id alone when the model name is not). A virtual machine's model name alone
    ("Intel(R) Xeon(R) Processor @ 2.80GHz") covers several CPUs: the same
    code gave Embree's best mode over ours a median of 0.96 on one such
    machine and 0.87 on another (README, "Against Embree 3"), so records
    that name the CPU by model name only are not taken for the same CPU as
    those that name it fully. None when the CPU is unknown."""
    if not prov:
        return None
    known = [prov[k] for k in ("cpu_id", "cpu_caches") if prov.get(k)]
    if not prov.get("cpu_model"):
        return "; ".join(known) or None
    return prov["cpu_model"] + (" (%s)" % "; ".join(known) if known else "")


def short(prov, cpu=False):
    """A provenance in a few words: commit[:12], "+dirty <tree[:12]>" when
    dirty, the compilation mode (and the CPU when asked)."""
    if prov is None:
        return 'unknown provenance (records without "provenance")'
    text = (prov.get("commit") or "unknown commit")[:12]
    if prov.get("dirty"):
        text += " +dirty %s" % (prov.get("source_tree") or "unknown tree")[:12]
    text += ", %s" % (prov.get("compilation_mode") or "unknown mode")
    if cpu:
        text += ", %s" % (cpu_name(prov) or "unknown CPU")
    return text


def _label(record):
    """scene/preset (or whatever of scene, preset, step, mode it has)."""
    parts = [str(record[k]) for k in ("scene", "preset", "step", "mode")
             if record.get(k) is not None]
    return "/".join(parts) or "a record"


def groups(records, key):
    """[(provenance, [records])] by key(provenance), in order first seen."""
    out = {}
    for rec in records:
        prov = of(rec)
        out.setdefault(key(prov), (prov, []))[1].append(rec)
    return list(out.values())


def _describe(grouped, cpu):
    return "; ".join("%s (%d record%s, e.g. %s)"
                     % (short(p, cpu), len(recs), "" if len(recs) == 1 else "s",
                        _label(recs[0])) for p, recs in grouped)


def check_one_provenance(records, allow_mixed=False, allow_mixed_cpus=False,
                         what="one table"):
    """Raises ProvenanceError when the records come from more than one code
    (source tree, compilation mode), MixedCpuError when from more than one
    CPU (cpu_name), unless allowed; returns [(provenance, [records])] of the
    distinct provenances (code and CPU)."""
    records = list(records)
    by_code = groups(records, code_key)
    if len(by_code) > 1 and not allow_mixed:
        raise ProvenanceError(
            "%s would mix records of %d provenances: %s. Rerun them with one "
            "build of one source tree, or pass --allow_mixed_provenance"
            % (what, len(by_code), _describe(by_code, False)))
    cpus = sorted({cpu_name(p) for p in map(of, records)} - {None})
    if len(cpus) > 1 and not allow_mixed_cpus:
        raise MixedCpuError(
            "%s: timings from %d different CPUs (%s) would be mixed; rerun "
            "on one kind of node, or pass --allow_mixed_cpus"
            % (what, len(cpus), "; ".join(cpus)))
    return groups(records, lambda p: (code_key(p), cpu_name(p)))


def check_timing_builds(records, allow=False, what="one table"):
    """Raises UnoptimizedTimingError naming the first record whose binary was
    not built for timing (provenance timing_build false), unless allowed. An
    unknown provenance is not refused (the report's first page says it is
    unknown)."""
    if allow:
        return
    for rec in records:
        prov = of(rec)
        if prov is not None and not prov.get("timing_build"):
            raise UnoptimizedTimingError(
                "%s would show timings of %s from a binary not built for "
                "timing (%s: optimized %s, ndebug %s); rebuild with bazel -c "
                "opt and rerun, or pass --allow_unoptimized_timings"
                % (what, _label(rec), short(prov), prov.get("optimized"),
                   prov.get("ndebug")))


def check(ctx, records, what, timings=True):
    """Both checks with the context's override flags (make_all's command
    line); returns the distinct provenances as check_one_provenance."""
    records = list(records)
    out = check_one_provenance(
        records, getattr(ctx, "allow_mixed_provenance", False),
        getattr(ctx, "allow_mixed_cpus", False), what)
    if timings:
        check_timing_builds(
            records, getattr(ctx, "allow_unoptimized_timings", False), what)
    return out


def frame_records(df):
    """The records behind a kdtree_results frame, as far as the checks need
    them: scene, preset and provenance."""
    if df.empty:
        return []
    return [{"scene": s, "preset": v, "provenance": p}
            for (s, v), p in df["provenance"].items()]


def check_frame(ctx, df, what, timings=True):
    return check(ctx, frame_records(df), what, timings)


def cpus(grouped):
    return sorted({cpu_name(p) for p, _ in grouped} - {None})
