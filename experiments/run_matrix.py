#!/usr/bin/python3
"""Runs the experiment matrix: every variant of experiments/matrix.json on
every obtained scene of a profile, with //cc/tools:kdrt.

    /usr/bin/python3 experiments/run_matrix.py --profile quick \
        [--kdrt bazel-out/k8-opt/bin/cc/tools/kdrt] [--out out]

Each (scene, variant) runs kdrt once (kdrt warms each tracer up untimed, then
times --repeats rounds alternating the kd-tree and Embree and keeps the
median; a profile's "repeat_budget_s" stops the rounds of a step that took
that long in all). Locally, --jobs (or the profile's "jobs") kdrt processes
run at once: their untimed work (loading, warm-ups, counting passes, the
Embree comparison) overlaps, their timed rounds never do (each holds the
machine-wide timing lock, cc/base/timing_lock.h; the record's
provenance.timed_beside is 0). The record kdrt writes is appended,
with the profile and the runner's wall time, to OUT/results/kdtree.jsonl;
a failure is appended as {"ok": false, ...} with the end of kdrt's stderr.
Raw results are append-only: nothing is ever rewritten.

Resumable: a (scene, variant, repeats, threads, embree, source tree) already
recorded with "ok": true is not run again (--force runs it again; the
analysis keeps the newest record). The source tree is the code identity of
cc/base/source_id.sh (experiments/provenance.py): any edit to the tools'
sources, build files, presets or scene manifest, committed or not, gives a
new one, and every job runs again under it (the simple first version: no
attempt to tell which jobs an edit affects). The binary must be built from the
same checkout (reproduce.sh builds it first). Images go to OUT/images/<scene>_<variant>.png.
With --backend slurm the pending jobs go to a SLURM cluster as one
`sbatch --array` (task i runs job i of OUT/slurm/<stamp>/jobs.json, and
writes its record to parts/i.json). The command waits for the array, then
appends the records in job order, so the results file has the same records
as a local run. A task without a record is reported with its log. Scene data
must be fetched before (tasks never download): reproduce.sh does that. The
backend is experiments/matrix_slurm.py.

Standard library only (tqdm for the progress bar and ETA when present).
"""

import argparse
import concurrent.futures
import json
import os
import socket
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))

import jsonl  # noqa: E402  (the results files' one reader and appender)
import provenance  # noqa: E402  (the code identity of the checkout)
import run_scenes  # noqa: E402  (manifest/index readers)

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
    """What makes two runs the same job: the scene, the variant, the
    profile's settings and the code (settings["source_tree"], the checkout's
    identity when the plan was made)."""
    key = (scene, variant, int(settings["repeats"]), int(settings["threads"]),
           embree_mode(variant, settings), settings.get("source_tree"))
    # A run that times more, or writes a cost image, is another job (an
    # older run of the same code without it is not done): matrix.json is not
    # part of the source tree.
    if variant in settings.get("fast_render", []):
        key += ("fast_render",)
    if wants_triangle_bvh(variant, settings):
        key += ("triangle_bvh",)
    return key + ("cost_image",) if wants_cost_image(scene, settings) else key


def wants_triangle_bvh(variant, settings):
    """Whether kdrt also times the baseline over whole triangles (matrix.json's
    triangle_bvh_variants, in the fast mode, with Embree timed: its ratios
    are to Embree)."""
    return (variant in settings.get("triangle_bvh", [])
            and variant in settings.get("fast_render", [])
            and settings["embree"] != "off" and embree_timed(variant, settings))


def wants_cost_image(scene, settings):
    """Whether kdrt writes the scene's cost image (matrix.json's
    cost_image_scenes): per-pixel N_TR / N_IT, cc/render/cost_image.h."""
    return scene in settings.get("cost_images", [])


def embree_timed(variant, settings):
    """Whether Embree runs in the variant's timed rounds: on the variants of
    matrix.json's embree_timed_variants (all when the list is absent); on
    the others it is built once, untimed, to compare every ray."""
    timed = settings.get("embree_timed")
    return timed is None or variant in timed


def embree_mode(variant, settings):
    """The profile's Embree setting as the job runs it: "off", the quality,
    or the quality and " untimed" (comparison only)."""
    mode = settings["embree"]
    if mode == "off" or embree_timed(variant, settings):
        return mode
    return mode + " untimed"


def done_keys(results_path):
    """Keys of the successful records already in results_path that came from
    an optimised build (provenance.timing_build: the analysis refuses the
    timings of any other, so such a job is not done)."""
    keys = set()
    for rec in jsonl.read_resuming(results_path, "resume"):
        prov = rec.get("provenance") or {}
        if rec.get("ok") and prov.get("timing_build", True):
            keys.add(tuple(rec["job"]))
    return keys


def plan(profile, matrix, manifest, index, scenes=None, variants=None):
    """[(scene_name, mesh_path, variant)] in manifest order, variants inner
    (the report's nine, then the beyond_variants)."""
    names = [s["name"] for s in manifest if profile in s.get("profiles", [])]
    if scenes:
        names = [n for n in names if n in scenes]
    every = matrix["variants"] + matrix.get("beyond_variants", [])
    chosen = [v for v in every if not variants or v in variants]
    return [(n, index[n], v) for n in names if n in index for v in chosen]


def kdrt_command(kdrt, scene, variant, settings, image=None, cost_image=None):
    # The preset by name (experiments/presets/<variant>.env holds the same
    # configuration, checked by //cc/kdtree:env_file_test).
    cmd = [kdrt, "--scene", scene, "--preset", variant,
           "--repeats", str(settings["repeats"]),
           "--threads", str(settings["threads"]),
           "--embree", settings["embree"]]
    if settings["embree"] != "off" and not embree_timed(variant, settings):
        cmd += ["--noembree_rounds"]
    if settings.get("repeat_budget_s"):
        cmd += ["--repeat_budget_s", str(settings["repeat_budget_s"])]
    if variant in settings.get("fast_render", []):
        # Also the renderer's fastest mode (kdrt --fast_render: record field
        # fast_render, the analysis's T_R_fast).
        cmd += ["--fast_render"]
    if wants_triangle_bvh(variant, settings):
        # And the same kernels over a BVH of whole triangles (record field
        # fast_render.triangle_bvh): what the kd-tree's structure costs.
        cmd += ["--triangle_bvh"]
    if cost_image:
        cmd += ["--cost_image", cost_image]
    return cmd + ["--image", image] if image else cmd


def run_kdrt(cmd):
    """Runs a kdrt command line; kdrt prints its record on stdout (and writes
    its image where --image says). Returns (returncode, stderr, the records
    printed, wall seconds, the command)."""
    start = time.time()
    proc = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    wall = time.time() - start
    lines = []
    for line in proc.stdout.splitlines():
        try:
            lines.append(json.loads(line))
        except ValueError:
            pass  # not a record
    return proc.returncode, proc.stderr, lines, wall, cmd


def node_info():
    """Where a record was measured: host and, under SLURM, job and task."""
    info = {"host": socket.gethostname()}
    for var in ("SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID",
                "SLURMD_NODENAME"):
        if os.environ.get(var):
            info[var.lower()] = os.environ[var]
    return info


def run_job(kdrt, scene, variant, settings, out, profile):
    """Runs kdrt for one job; returns the record to append. The image goes
    to OUT/images/<scene>_<variant>.png, the cost image (when the scene
    has one) to OUT/costs/<scene>_<variant>.npy.gz."""
    image = os.path.join(os.path.abspath(out), "images",
                         "%s_%s.png" % (scene, variant))
    cost = (os.path.join(os.path.abspath(out), "costs", "%s_%s.npy.gz" % (scene, variant))
            if wants_cost_image(scene, settings) else None)
    cmd = kdrt_command(kdrt, scene, variant, settings, image, cost)
    returncode, stderr, lines, wall, cmd = run_kdrt(cmd)
    if returncode != 0 or not lines:
        return {"ok": False, "job": job_key(scene, variant, settings),
                "scene": scene, "preset": variant, "profile": profile,
                "returncode": returncode, "wall_s": wall,
                "command": cmd, "error": stderr[-2000:]}
    rec = lines[-1]
    rec.update({"ok": True, "job": job_key(scene, variant, settings),
                "profile": profile, "wall_s": wall, "node": node_info()})
    return rec


def run_concurrently(items, run, jobs_at_once):
    """Yields run(item) for every item, `jobs_at_once` at a time, each as it
    ends (so its record is appended at once). When the caller stops early or
    is interrupted, the runs not yet started are dropped; those running finish
    (a kdrt process is never killed mid-way). The matrix and the accuracy
    study (experiments/run_accuracy.py) both run their kdrt jobs through it."""
    pool = concurrent.futures.ThreadPoolExecutor(max(1, jobs_at_once))
    try:
        futures = [pool.submit(run, item) for item in items]
        for fut in concurrent.futures.as_completed(futures):
            yield fut.result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def run_local(pending, settings, args, results_path, jobs_at_once):
    """Runs the pending jobs here, `jobs_at_once` kdrt processes at a time
    (each single-threaded unless the profile says otherwise); appends each
    record as it finishes. Returns the number of failures."""
    bar = _tqdm(total=len(pending), unit="run", file=sys.stderr) if _tqdm \
        else None
    failures = 0

    def one(job):
        scene, _, variant = job
        rec = run_job(args.kdrt, scene, variant, settings, args.out,
                      args.profile)
        rec["backend"] = "local"
        rec["concurrent_jobs"] = jobs_at_once
        return rec

    for rec in run_concurrently(pending, one, jobs_at_once):
        jsonl.append(results_path, rec)
        if not rec["ok"]:
            failures += 1
            print("run_matrix: %s/%s failed (exit %s): %s"
                  % (rec["scene"], rec["preset"], rec["returncode"],
                     rec["error"].strip().splitlines()[-1:] or ""),
                  file=sys.stderr)
        if bar:
            bar.set_description("%s/%s" % (rec["scene"], rec["preset"]))
            bar.update(1)
    if bar:
        bar.close()
    return failures


def add_kdrt_flag(parser):
    """--kdrt, as the runners of experiments/ take it: the --config=opt
    build's by default (never bazel-bin, which follows the last build)."""
    parser.add_argument("--kdrt", default=provenance.opt_binary("cc", "tools", "kdrt"),
                        help="kdrt binary (default: %(default)s, the --config=opt build's)")


def kdrt_missing(kdrt, who):
    """True, after saying so on stderr, when there is no kdrt binary at kdrt."""
    if os.path.exists(kdrt):
        return False
    print("%s: no kdrt binary at %s" % (who, kdrt), file=sys.stderr)
    return True


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--profile", default="quick")
    p.add_argument("--out", default=os.path.join(ROOT, "out"))
    add_kdrt_flag(p)
    p.add_argument("--manifest", default=run_scenes.DEFAULT_MANIFEST)
    p.add_argument("--index", default=run_scenes.DEFAULT_INDEX)
    p.add_argument("--scenes", default="", help="comma-separated subset")
    p.add_argument("--variants", default="", help="comma-separated subset")
    p.add_argument("--repeats", type=int, help="override the profile's")
    p.add_argument("--embree", help="override the profile's (off|low|medium|high)")
    p.add_argument("--force", action="store_true")
    p.add_argument("--jobs", type=int, help="local runs at once (default: "
                   "the profile's 'jobs', else 1); each record notes it")
    p.add_argument("--backend", choices=["local", "slurm"], default="local",
                   help="local: here, --jobs runs at a time; slurm: one "
                   "sbatch --array over the pending jobs")
    p.add_argument("--partition", help="SLURM partition (default: the "
                   "cluster's default)")
    p.add_argument("--time", default="02:00:00", help="SLURM time limit per task")
    p.add_argument("--mem", default="16G", help="SLURM memory per task")
    p.add_argument("--max_parallel", type=int, default=0,
                   help="SLURM tasks at once (0: no limit)")
    p.add_argument("--task", help=argparse.SUPPRESS)  # jobs.json of an array
    p.add_argument("--task_index", type=int, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.task:
        import matrix_slurm  # noqa: E402  (the SLURM backend; it imports this module)
        return matrix_slurm.run_task(args.task, args.task_index, args.kdrt, args.out)

    matrix = load_matrix()
    if args.profile not in matrix["profiles"]:
        print("run_matrix: unknown profile %r" % args.profile, file=sys.stderr)
        return 2
    settings = dict(matrix["profiles"][args.profile])
    settings["fast_render"] = matrix.get("fast_render_variants", [])
    settings["embree_timed"] = matrix.get("embree_timed_variants")
    settings["triangle_bvh"] = matrix.get("triangle_bvh_variants", [])
    settings["cost_images"] = matrix.get("cost_image_scenes", [])
    if args.repeats:
        settings["repeats"] = args.repeats
    if args.embree:
        settings["embree"] = args.embree
    ident = provenance.pin()
    settings["source_tree"] = ident["source_tree"]
    print("run_matrix: code %s (source tree %s)"
          % (provenance.short(ident), ident["source_tree"]), file=sys.stderr)
    if kdrt_missing(args.kdrt, "run_matrix"):
        return 2
    manifest = run_scenes.load_manifest(args.manifest)
    try:
        index = run_scenes.load_index(args.index)
    except run_scenes.SetupError as e:
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
    if args.backend == "slurm":
        if not pending:
            return 0
        import matrix_slurm  # noqa: E402  (the SLURM backend; it imports this module)
        failures = matrix_slurm.run_slurm(pending, settings, args, results_path)
        print("run_matrix: %d SLURM tasks, %d failed" % (len(pending), failures),
              file=sys.stderr)
        return 0
    jobs_at_once = max(1, args.jobs or int(settings.get("jobs", 1)))
    failures = run_local(pending, settings, args, results_path, jobs_at_once)
    print("run_matrix: %d runs, %d failed" % (len(pending), failures),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    # matrix_slurm imports this module by name: let it find this one rather
    # than load a second copy.
    sys.modules.setdefault("run_matrix", sys.modules["__main__"])
    sys.exit(main())
