"""run_matrix.py's SLURM backend (--backend slurm): the pending jobs as one
`sbatch --array`, each task running one job through run_matrix.py --task
and writing its record to parts/<i>.json; the driver waits for the array and
appends the records in job order, so the results file holds what a local run
would have written. Checked against a local run on a live one-node cluster
by experiments/slurm/check.sh (CI runs it).

Standard library only.
"""

import json
import os
import subprocess
import sys
import time

import jsonl
import run_matrix


def run_task(jobs_file, index, kdrt, out):
    """One SLURM array task: job `index` of jobs_file; the record goes to
    parts/<index>.json beside it (written atomically), never to the shared
    results file (the driver merges the parts in order)."""
    with open(jobs_file, encoding="utf-8") as f:
        spec = json.load(f)
    job = spec["jobs"][index]
    rec = run_matrix.run_job(kdrt, job["scene"], job["variant"], spec["settings"], out,
                             spec["profile"])
    parts = os.path.join(os.path.dirname(jobs_file), "parts")
    os.makedirs(parts, exist_ok=True)
    tmp = os.path.join(parts, "%d.json.tmp" % index)
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(rec, f)
    os.rename(tmp, os.path.join(parts, "%d.json" % index))
    return 0 if rec["ok"] else 1


def run_slurm(pending, settings, args, results_path):
    """Submits the pending jobs as one `sbatch --array`, waits for it, and
    appends every task's record (or a failure naming its log) in job order.
    Returns the number of failed tasks."""
    stamp = time.strftime("%Y%m%d-%H%M%S")
    work = os.path.abspath(os.path.join(args.out, "slurm", stamp))
    os.makedirs(os.path.join(work, "logs"), exist_ok=True)
    jobs_file = os.path.join(work, "jobs.json")
    with open(jobs_file, "w", encoding="utf-8") as f:
        json.dump({"profile": args.profile, "settings": settings,
                   "jobs": [{"scene": s, "variant": v} for s, _, v in pending]},
                  f, indent=1)
    script = os.path.join(work, "task.sh")
    with open(script, "w", encoding="utf-8") as f:
        f.write("#!/bin/bash\n# One (scene, variant) of %s per array task.\n"
                "exec /usr/bin/python3 %s --task %s --task_index "
                "\"$SLURM_ARRAY_TASK_ID\" --kdrt %s --out %s\n"
                % (jobs_file, os.path.abspath(run_matrix.__file__), jobs_file,
                   os.path.abspath(args.kdrt), os.path.abspath(args.out)))
    os.chmod(script, 0o755)
    array = "0-%d" % (len(pending) - 1)
    if args.max_parallel:
        array += "%%%d" % args.max_parallel
    cmd = ["sbatch", "--parsable", "--wait", "--array=" + array,
           "--job-name=kdtree-" + args.profile,
           "--output=" + os.path.join(work, "logs", "%A_%a.out"),
           "--cpus-per-task=%d" % max(1, int(settings["threads"])),
           "--chdir=" + run_matrix.ROOT]
    for flag, value in (("--partition", args.partition), ("--time", args.time),
                        ("--mem", args.mem)):
        if value:
            cmd.append("%s=%s" % (flag, value))
    cmd.append(script)
    print("run_matrix: %s" % " ".join(cmd), file=sys.stderr)
    start = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True)
    job_id = proc.stdout.strip().split(";")[0]
    print("run_matrix: array job %s finished in %.1f s (sbatch exit %d)"
          % (job_id or "?", time.time() - start, proc.returncode),
          file=sys.stderr)
    if not job_id:
        raise RuntimeError("sbatch failed: %s" % proc.stderr.strip())
    failures = 0
    for i, (scene, _, variant) in enumerate(pending):
        part = os.path.join(work, "parts", "%d.json" % i)
        log = os.path.join(work, "logs", "%s_%d.out" % (job_id, i))
        if os.path.exists(part):
            with open(part, encoding="utf-8") as f:
                rec = json.load(f)
        else:
            tail = ""
            if os.path.exists(log):
                with open(log, encoding="utf-8", errors="replace") as f:
                    tail = f.read()[-2000:]
            rec = {"ok": False, "job": run_matrix.job_key(scene, variant, settings),
                   "scene": scene, "preset": variant, "profile": args.profile,
                   "returncode": None, "error": "no record from SLURM task "
                   "%s_%d; log %s:\n%s" % (job_id, i, log, tail)}
        rec["backend"] = "slurm"
        jsonl.append(results_path, rec)
        if not rec["ok"]:
            failures += 1
            print("run_matrix: task %s_%d (%s/%s) failed; log: %s"
                  % (job_id, i, scene, variant, log), file=sys.stderr)
    return failures
