"""Macros describing where the results were measured (results/machine.json,
written by experiments/run_scenes.py)."""

from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance as pv


def macros(machine):
    commit = machine.get("git_commit") or "unknown"
    memory = machine.get("memory_gib")
    return {
        "MachineCPU": (machine.get("cpu_model") or "unknown CPU", False),
        "MachineCores": (machine.get("cpu_count") or "?", False),
        "MachineMemory": (
            ("%s\\,GiB" % latex.fmt_float(memory, 3)) if memory else "?", True),
        "MachineOS": (machine.get("os") or "unknown OS", False),
        "MachineCompiler": (machine.get("compiler") or "unknown compiler",
                            False),
        "GitCommit": (commit[:12], False),
        "GitCommitFull": (commit, False),
        "GitDirty": (" (with uncommitted changes)"
                     if machine.get("git_dirty") else "", False),
        "ResultsDate": ((machine.get("recorded_at") or "unknown")[:10], False),
    }


def records_cpu(records, model):
    """What the records add to the machine's model name `model`: " (family,
    model, stepping; caches)" (provenance.cpu_name less the model name) when
    every record that names a CPU names the same one, of that model; else
    "". The records say where the timings ran; machine.json, where
    run_scenes.py last ran (an older machine.json has the model name only,
    which a virtual machine shares with other CPUs)."""
    names = {pv.cpu_name(pv.of(r)) for r in records} - {None}
    if len(names) != 1 or not model:
        return ""
    # An older machine.json's model name has its runs of spaces collapsed;
    # the records' is /proc/cpuinfo's own.
    name, model = " ".join(names.pop().split()), " ".join(model.split())
    return name[len(model):] if name.startswith(model) else ""


def generate(ctx):
    machine = ctx.machine
    if not machine:
        raise RuntimeError("no %s/machine.json: run experiments/run_scenes.py "
                           "first" % ctx.results_dir)
    out = macros(machine)
    out["MachineCPUDetail"] = (records_cpu(kr.latest(ctx.results(kr.KDTREE_FILE)).values(),
                                           machine.get("cpu_model")), False)
    return out
