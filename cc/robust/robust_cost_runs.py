"""The robustness cost runs of cc/robust/robust_suite.py (its docstring says
what they are): which (scene, preset) runs a profile needs, which the results
already hold for the same code, and running robust_cost_bench on the rest.

Standard library only.
"""

import importlib.util
import json
import os
import subprocess
import sys

GENERATED = "generated"  # the cost bench's own scene (every preset)


def load_experiments_module(name):
    """experiments/<name>.py beside this file's checkout (in Bazel's runfiles
    too: a data dependency), loaded under its own name "experiments_<name>":
    the one implementation of what it does (provenance: the code identity and
    the machine's fields; jsonl: the results files' reader)."""
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), "experiments", name + ".py")
    spec = importlib.util.spec_from_file_location("experiments_" + name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


JSONL = load_experiments_module("jsonl")


def read_records(path):
    """The records of a results file, for resuming: a line cut short by an
    interrupted run is passed over with a warning (experiments/jsonl.py
    read_resuming)."""
    return JSONL.read_resuming(path, "robust_suite")


def short_tree(tree):
    """A source tree id's first 12 characters, for messages."""
    return (tree or "unknown")[:12]


def list_presets(bench):
    """The bench's own preset list (robust_cost_bench --list_presets)."""
    listed = subprocess.run([bench, "--list_presets"], stdout=subprocess.PIPE,
                            universal_newlines=True, check=True).stdout
    return [p for p in listed.strip().split(",") if p]


def profile_scenes(manifest_path, index_path, profile):
    """Names of the profile's scenes that are in the fetched index."""
    with open(manifest_path, encoding="utf-8") as f:
        manifest = json.load(f)
    fetched = {}
    if os.path.exists(index_path):
        with open(index_path, encoding="utf-8") as f:
            fetched = json.load(f).get("scenes", {})
    return [s["name"] for s in manifest["scenes"]
            if profile in s.get("profiles", []) and s["name"] in fetched]


def generated_presets(matrix_path):
    """"default", then the matrix's variants and beyond_variants."""
    with open(matrix_path, encoding="utf-8") as f:
        matrix = json.load(f)
    return (["default"] + list(matrix["variants"])
            + list(matrix.get("beyond_variants", [])))


def done_runs(cost_out, source_tree, repeats=1):
    """(scene, preset) pairs cost_out already holds from source_tree (not
    None), from a timing build, with paired rounds, at least `repeats` of
    them. Records of other code, of the old unpaired format or without
    provenance do not count."""
    done = set()
    if not source_tree:
        return done
    for rec in read_records(cost_out):
        prov = rec.get("provenance")
        if (isinstance(prov, dict) and prov.get("source_tree") == source_tree
                and prov.get("timing_build")
                and len(rec.get("paired_ratio_runs") or []) >= repeats
                and rec.get("scene") and rec.get("preset")):
            done.add((rec["scene"], rec["preset"]))
    return done


def cost_jobs(scenes, presets_generated, done):
    """[(scene, presets still to run)] for the profile's scenes (default
    preset) and the generated scene (every preset); finished ones left out."""
    jobs = [(s, ["default"]) for s in scenes]
    jobs.append((GENERATED, list(presets_generated)))
    out = []
    for scene, presets in jobs:
        todo = [p for p in presets if (scene, p) not in done]
        if todo:
            out.append((scene, todo))
    return out


def run_cost(bench, cost_out, scenes, repeats=5, log=None,
             presets_generated=None, source_tree=None):
    """Runs the cost bench per scene (default preset) and on the generated
    scene (every preset), skipping (scene, preset) runs of source_tree
    already in cost_out; returns failures."""
    log = log or sys.stderr
    os.makedirs(os.path.dirname(os.path.abspath(cost_out)), exist_ok=True)
    if presets_generated is None:  # the bench's own list
        presets_generated = list_presets(bench)
    done = done_runs(cost_out, source_tree, repeats)
    jobs = cost_jobs(scenes, presets_generated, done)
    skipped = len(scenes) + len(presets_generated) - sum(len(p) for _, p in jobs)
    if skipped:
        print("robust_suite: cost: %d (scene, preset) runs of source tree %s "
              "already in %s, not rerun" % (skipped, short_tree(source_tree),
                                            cost_out), file=log, flush=True)
    failed = 0
    for scene, presets in jobs:
        args = [] if scene == GENERATED else ["--scene", scene]
        print("robust_suite: cost on %s (%s)" % (scene, ",".join(presets)),
              file=log, flush=True)
        proc = subprocess.run([bench] + args + [
            "--presets", ",".join(presets), "--out", cost_out,
            "--repeats", str(repeats)], check=False)
        if proc.returncode != 0:
            failed += 1
            print("robust_suite: cost bench failed on %s (exit %d)"
                  % (scene, proc.returncode), file=log)
    return failed
