#!/usr/bin/python3
"""Runs the experiment matrix: every variant of experiments/matrix.json on
every obtained scene of a profile, with //cc/tools:kdrt.

    /usr/bin/python3 experiments/run_matrix.py --profile quick \
        --kdrt "$(bazel info -c opt bazel-bin)/cc/tools/kdrt" [--out out]

Each (scene, variant) runs kdrt once (kdrt itself repeats build and render
--repeats times and keeps the median). The record kdrt writes is appended,
with the profile and the runner's wall time, to OUT/results/kdtree.jsonl;
a failure is appended as {"ok": false, ...} with the end of kdrt's stderr.
Raw results are append-only: nothing is ever rewritten.

Resumable: a (scene, variant, repeats, threads, embree) already recorded with
"ok": true is not run again (--force runs it again; the analysis keeps the
newest record). Images go to OUT/images/<scene>_<variant>.png.
Standard library only (tqdm for the progress bar and ETA when present).
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))

import scenes as scene_runner  # noqa: E402  (manifest/index readers)

MATRIX = os.path.join(ROOT, "experiments", "matrix.json")
RESULTS_FILE = "kdtree.jsonl"

try:
    from tqdm import tqdm as _tqdm
except ImportError:
    _tqdm = None


def load_matrix(path=MATRIX):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def job_key(scene, variant, settings):
    return (scene, variant, int(settings["repeats"]), int(settings["threads"]),
            settings["embree"])


def done_keys(results_path):
    """Keys of the successful records already in results_path."""
    keys = set()
    if not os.path.exists(results_path):
        return keys
    with open(results_path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            rec = json.loads(line)
            if rec.get("ok"):
                keys.add(tuple(rec["job"]))
    return keys


def plan(profile, matrix, manifest, index, scenes=None, variants=None):
    """[(scene_name, mesh_path, variant)] in manifest order, variants inner."""
    names = [s["name"] for s in manifest if profile in s.get("profiles", [])]
    if scenes:
        names = [n for n in names if n in scenes]
    chosen = [v for v in matrix["variants"] if not variants or v in variants]
    return [(n, index[n], v) for n in names if n in index for v in chosen]


def kdrt_command(kdrt, scene, variant, settings, out_dir):
    cmd = [kdrt, "--scene", scene,
           "--env", os.path.join(ROOT, "experiments", "presets",
                                 variant + ".env"),
           "--preset", variant,
           "--repeats", str(settings["repeats"]),
           "--threads", str(settings["threads"]),
           "--embree", settings["embree"],
           "--out", out_dir]
    return cmd


def run_job(kdrt, scene, variant, settings, out, profile):
    """Runs kdrt for one job; returns the record to append."""
    tmp = tempfile.mkdtemp(prefix="kdrt-", dir=out)
    start = time.time()
    cmd = kdrt_command(kdrt, scene, variant, settings, tmp)
    try:
        proc = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
        wall = time.time() - start
        lines = []
        results = os.path.join(tmp, "results.jsonl")
        if os.path.exists(results):
            with open(results, encoding="utf-8") as f:
                lines = [json.loads(x) for x in f if x.strip()]
        if proc.returncode != 0 or not lines:
            return {"ok": False, "job": job_key(scene, variant, settings),
                    "scene": scene, "preset": variant, "profile": profile,
                    "returncode": proc.returncode, "wall_s": wall,
                    "command": cmd, "error": proc.stderr[-2000:]}
        rec = lines[-1]
        rec.update({"ok": True, "job": job_key(scene, variant, settings),
                    "profile": profile, "wall_s": wall})
        images = os.path.join(out, "images")
        os.makedirs(images, exist_ok=True)
        for name in os.listdir(tmp):
            if name.endswith(".png"):
                shutil.move(os.path.join(tmp, name),
                            os.path.join(images, "%s_%s.png" % (scene, variant)))
        return rec
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--profile", default="quick")
    p.add_argument("--out", default=os.path.join(ROOT, "out"))
    p.add_argument("--kdrt", default=os.path.join(ROOT, "bazel-bin", "cc",
                                                  "tools", "kdrt"))
    p.add_argument("--manifest", default=scene_runner.DEFAULT_MANIFEST)
    p.add_argument("--index", default=scene_runner.DEFAULT_INDEX)
    p.add_argument("--scenes", default="", help="comma-separated subset")
    p.add_argument("--variants", default="", help="comma-separated subset")
    p.add_argument("--repeats", type=int, help="override the profile's")
    p.add_argument("--embree", help="override the profile's (off|low|medium|high)")
    p.add_argument("--force", action="store_true")
    args = p.parse_args(argv)

    matrix = load_matrix()
    if args.profile not in matrix["profiles"]:
        print("run_matrix: unknown profile %r" % args.profile, file=sys.stderr)
        return 2
    settings = dict(matrix["profiles"][args.profile])
    if args.repeats:
        settings["repeats"] = args.repeats
    if args.embree:
        settings["embree"] = args.embree
    if not os.path.exists(args.kdrt):
        print("run_matrix: no kdrt binary at %s" % args.kdrt, file=sys.stderr)
        return 2
    manifest = scene_runner.load_manifest(args.manifest)
    try:
        index = scene_runner.load_index(args.index)
    except scene_runner.SetupError as e:
        print("run_matrix: %s" % e, file=sys.stderr)
        return 2
    jobs = plan(args.profile, matrix, manifest, index,
                [s for s in args.scenes.split(",") if s],
                [v for v in args.variants.split(",") if v])
    results_dir = os.path.join(args.out, "results")
    os.makedirs(results_dir, exist_ok=True)
    results_path = os.path.join(results_dir, RESULTS_FILE)
    done = set() if args.force else done_keys(results_path)
    pending = [j for j in jobs
               if job_key(j[0], j[2], settings) not in done]
    print("run_matrix: profile %s: %d jobs, %d already done, %d to run"
          % (args.profile, len(jobs), len(jobs) - len(pending), len(pending)),
          file=sys.stderr)
    bar = _tqdm(total=len(pending), unit="run", file=sys.stderr) if _tqdm \
        else None
    failures = 0
    for scene, _, variant in pending:
        if bar:
            bar.set_description("%s/%s" % (scene, variant))
        rec = run_job(args.kdrt, scene, variant, settings, args.out,
                      args.profile)
        with open(results_path, "a", encoding="utf-8") as f:
            f.write(json.dumps(rec) + "\n")
            f.flush()
            os.fsync(f.fileno())
        if not rec["ok"]:
            failures += 1
            print("run_matrix: %s/%s failed (exit %s): %s"
                  % (scene, variant, rec["returncode"],
                     rec["error"].strip().splitlines()[-1:] or ""),
                  file=sys.stderr)
        if bar:
            bar.update(1)
    if bar:
        bar.close()
    print("run_matrix: %d runs, %d failed" % (len(pending), failures),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
