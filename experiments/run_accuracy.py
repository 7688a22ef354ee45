#!/usr/bin/python3
"""Runs the accuracy-versus-time study of experiments/accuracy.json.

    /usr/bin/python3 experiments/run_accuracy.py --profile quick \
        [--kdrt bazel-out/k8-opt/bin/cc/tools/kdrt] [--out out]

For every scene of the profile and every step, kdrt builds and renders with
--preset PRESET and an environment file holding the step's options (written
to OUT/accuracy/envs/). The record kdrt writes gets the step's knob, name
and options and is appended to OUT/results/accuracy.jsonl (append-only; a
failure is appended as {"ok": false, ...}). Resumable: a (scene, step,
repeats) already recorded with "ok": true is skipped. --jobs kdrt processes
run at once (default: the profile's "jobs", else 1), like the matrix's: their
untimed work overlaps, their timed steps never do (cc/base/timing_lock.h);
records are appended as runs end (run_matrix.run_concurrently). Reuses
experiments/run_matrix.py's record and host helpers. Standard library only.
"""

import argparse
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))

import jsonl  # noqa: E402
import provenance  # noqa: E402
import run_matrix  # noqa: E402
import run_scenes  # noqa: E402

STUDY = os.path.join(ROOT, "experiments", "accuracy.json")
RESULTS_FILE = "accuracy.jsonl"
BINNING_KEYS = ("useBinning", "useDrivingAxis", "bins")


def env_text(options):
    """The environment file of a step: its options in the KDTree block."""
    inner = "".join("    %s %s\n" % (k, v) for k, v in options.items()
                    if k not in BINNING_KEYS)
    binning = "".join("        %s %s\n" % (k, v) for k, v in options.items()
                      if k in BINNING_KEYS)
    if binning:
        inner += "    Binning {\n%s    }\n" % binning
    return "KDTree {\n%s}\n" % inner


def slug(step):
    return re.sub(r"[^a-z0-9]+", "-", step.lower()).strip("-")


def job_key(scene, step, repeats, source_tree=None):
    """A step is done when recorded for this scene, repeats and code (the
    source tree of experiments/provenance.py: an edit reruns every step)."""
    return [scene, step["knob"], step["step"], int(repeats), source_tree]


def plan(profile_name, study, manifest, index, scenes=None):
    profile = study["profiles"][profile_name]
    names = profile["scenes"]
    if names == "manifest":
        names = [s["name"] for s in manifest
                 if profile_name in s.get("profiles", [])]
    if scenes:
        names = [n for n in names if n in scenes]
    return [(n, st) for n in names if n in index for st in study["steps"]]


def run_one(kdrt, scene, step, profile, profile_name, out, source_tree=None):
    env_dir = os.path.join(out, "accuracy", "envs")
    os.makedirs(env_dir, exist_ok=True)
    env_path = os.path.join(env_dir, slug(step["step"]) + ".env")
    # Atomic: another job of the same step may be reading it.
    tmp = "%s.%d.%s" % (env_path, os.getpid(), scene)
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(env_text(step["options"]))
    os.replace(tmp, env_path)
    cmd = [kdrt, "--scene", scene, "--preset", step["preset"],
           "--env", env_path, "--label", slug(step["step"]),
           "--repeats", str(profile["repeats"]), "--threads", "1",
           "--embree", "off"]
    if profile.get("repeat_budget_s"):
        cmd += ["--repeat_budget_s", str(profile["repeat_budget_s"])]
    returncode, stderr, lines, wall, cmd = run_matrix.run_kdrt(cmd)
    base = {"job": job_key(scene, step, profile["repeats"], source_tree),
            "scene": scene,
            "knob": step["knob"], "step": step["step"],
            "options": step["options"], "profile": profile_name,
            "wall_s": wall}
    if returncode != 0 or not lines:
        base.update({"ok": False, "returncode": returncode,
                     "command": cmd, "error": stderr[-2000:]})
        return base
    rec = lines[-1]
    rec.update(base)
    rec.update({"ok": True, "node": run_matrix.node_info()})
    return rec


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--profile", default="quick")
    run_matrix.add_kdrt_flag(parser)
    parser.add_argument("--out", default=os.path.join(ROOT, "out"))
    parser.add_argument("--study", default=STUDY)
    parser.add_argument("--manifest", default=run_scenes.DEFAULT_MANIFEST)
    parser.add_argument("--index", default=run_scenes.DEFAULT_INDEX)
    parser.add_argument("--scenes", default="",
                        help="comma-separated subset of the profile's scenes")
    parser.add_argument("--knobs", default="",
                        help="comma-separated subset of the knobs")
    parser.add_argument("--jobs", type=int,
                        help="kdrt processes at once (default: the profile's "
                        "'jobs', else 1)")
    parser.add_argument("--force", action="store_true",
                        help="run again steps already recorded (the analysis "
                        "keeps the newest record)")
    args = parser.parse_args(argv)
    if run_matrix.kdrt_missing(args.kdrt, "accuracy"):
        return 2
    with open(args.study, encoding="utf-8") as f:
        study = json.load(f)
    if args.profile not in study["profiles"]:
        print("accuracy: unknown profile %s" % args.profile, file=sys.stderr)
        return 2
    manifest = run_scenes.load_manifest(args.manifest)
    index = run_scenes.load_index(args.index)
    jobs = plan(args.profile, study, manifest, index,
                [s for s in args.scenes.split(",") if s])
    results_dir = os.path.join(args.out, "results")
    os.makedirs(results_dir, exist_ok=True)
    results_path = os.path.join(results_dir, RESULTS_FILE)
    done = run_matrix.done_keys(results_path)
    profile = study["profiles"][args.profile]
    knobs = [k for k in args.knobs.split(",") if k]
    if knobs:
        jobs = [(sc, st) for sc, st in jobs if st["knob"] in knobs]
    if args.force:
        done = set()
    failed = 0
    tree = provenance.pin()["source_tree"]
    pending = [(scene, step) for scene, step in jobs
               if tuple(job_key(scene, step, profile["repeats"], tree))
               not in done]
    jobs_at_once = max(1, min(args.jobs or profile.get("jobs", 1), len(pending)))

    def one(job):
        rec = run_one(os.path.abspath(args.kdrt), job[0], job[1], profile,
                      args.profile, args.out, tree)
        rec["concurrent_jobs"] = jobs_at_once
        return rec

    runs = run_matrix.run_concurrently(pending, one, jobs_at_once)
    for i, rec in enumerate(runs):
        jsonl.append(results_path, rec)
        failed += not rec["ok"]
        print("accuracy: [%d/%d] %s / %s: %s" % (
            i + 1, len(pending), rec["scene"], rec["step"],
            "T_B %.3f s, T_R %.3f s, SAH %.2f" % (
                rec["T_B"], rec["T_R"], rec.get("sah_cost", float("nan")))
            if rec["ok"] else "FAILED (%s)" % rec["error"][-300:]),
            file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
