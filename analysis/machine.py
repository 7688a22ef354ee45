"""Macros describing where the results were measured (results/machine.json,
written by experiments/run_scenes.py)."""

from analysis import latex


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


def generate(ctx):
    machine = ctx.machine
    if not machine:
        raise RuntimeError("no %s/machine.json: run experiments/run_scenes.py "
                           "first" % ctx.results_dir)
    return macros(machine)
