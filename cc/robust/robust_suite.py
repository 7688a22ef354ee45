"""Runs the adversarial suite and the robustness cost bench for the report.

Issue "Hard cases stay numerically stable": every kd-tree preset against
brute force on rays built to break traversal and intersection (Woop, Benthin
& Wald 2013 watertight test; Ize 2013 conservative traversal), and what the
watertight test costs against the fast one (Moeller & Trumbore 1997) on the
same rays.

    bazel build --config=opt //cc/robust:robust_suite //cc/robust:robust_cost_bench
    B=bazel-out/k8-opt/bin/cc/robust
    $B/robust_suite --out out/results/robust.jsonl \\
        --cost_bench $B/robust_cost_bench --cost_out out/results/robust_cost.jsonl \\
        --profile quick

Suite: each hard case is a gtest binary of cc/robust/BUILD (CASES below; run
without a filter, so every scene of a parametrised case runs) that checks
every preset against brute force and prints its numbers as `ROBUST_JSON {...}`
lines. Every such record is written to --out with "hard_case" (1-9) and
"binary" added, then one {"kind": "binary", ...} record per binary with its
exit status ("passed": the gtest assertions, 0 mismatches, held). The suite
is deterministic and rerun every time; --out is replaced only when all of it
ran (a failing case is recorded, not fatal).

Cost (with --cost_bench): robust_cost_bench on every scene of --profile
(data/manifest.json) that data/fetch.py fetched (data/cache/scenes/index.json),
preset "default", plus the generated scene with every preset. Appended to
--cost_out; a (scene, preset) already there is not rerun.
"""

import argparse
import json
import os
import subprocess
import sys
import time

# (hard case number, binary, what it checks); the binaries are data of the
# py_binary, so `bazel build` builds them in the same configuration.
CASES = [
    (1, "axis_rays_tiny_test", "axis-parallel rays on vertex and split grids"),
    (2, "split_origin_test", "origins exactly on split planes"),
    (3, "stairs_test", "stairs, analytic t"),
    (4, "flat_blocks_flat_test", "flat scene and voxel blocks"),
    (5, "watertight_sphere_origin_test", "watertight spheres at 0 and 1.5e5"),
    (6, "scale_blocks_test", "scale invariance 1e-4, 1, 1e4"),
    (7, "self_intersection_test", "shadow rays at magnitudes 1e-8..1e8"),
    (8, "garbage_test", "degenerate and garbage triangles"),
    (9, "image_test", "images equal brute force pixel for pixel"),
]

PREFIX = "ROBUST_JSON "
GENERATED = "generated"  # the cost bench's own scene (every preset)


def parse_records(stdout):
    """The ROBUST_JSON records of a binary's output, in order."""
    out = []
    for line in stdout.splitlines():
        if line.startswith(PREFIX):
            out.append(json.loads(line[len(PREFIX):]))
    return out


def run_suite(bin_dir, out_path, cases=CASES, log=sys.stderr):
    """Runs every case binary; writes --out; returns the number that failed."""
    records, failed = [], 0
    for number, binary, what in cases:
        path = os.path.join(bin_dir, binary)
        start = time.time()
        print("robust_suite: case %d (%s): %s" % (number, what, binary),
              file=log, flush=True)
        proc = subprocess.run([path], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, universal_newlines=True,
                              check=False)
        seconds = time.time() - start
        found = parse_records(proc.stdout)
        for rec in found:
            rec["hard_case"] = number
            rec["binary"] = binary
        records.extend(found)
        passed = proc.returncode == 0
        failed += not passed
        records.append({"kind": "binary", "hard_case": number,
                        "binary": binary, "what": what, "passed": passed,
                        "exit_code": proc.returncode, "records": len(found),
                        "seconds": round(seconds, 3)})
        print("robust_suite:   %s, %d records, %.1f s"
              % ("passed" if passed else "FAILED (exit %d)" % proc.returncode,
                 len(found), seconds), file=log, flush=True)
        if not passed:
            print(proc.stdout[-4000:], file=log)
    os.makedirs(os.path.dirname(os.path.abspath(out_path)), exist_ok=True)
    tmp = out_path + ".new"
    with open(tmp, "w", encoding="utf-8") as f:
        for rec in records:
            f.write(json.dumps(rec, sort_keys=True) + "\n")
    os.replace(tmp, out_path)
    return failed


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


def done_runs(cost_out):
    """(scene, preset) pairs already measured in cost_out."""
    done = set()
    if os.path.exists(cost_out):
        with open(cost_out, encoding="utf-8") as f:
            for line in f:
                line = line.strip()
                if line:
                    rec = json.loads(line)
                    done.add((rec["scene"], rec["preset"]))
    return done


def run_cost(bench, cost_out, scenes, repeats=5, log=sys.stderr):
    """Runs the cost bench per scene (default preset) and on the generated
    scene (every preset), skipping finished runs; returns failures."""
    os.makedirs(os.path.dirname(os.path.abspath(cost_out)), exist_ok=True)
    done = done_runs(cost_out)
    failed = 0
    jobs = [(s, ["--scene", s, "--presets", "default"], ["default"])
            for s in scenes]
    jobs.append((GENERATED, [], None))
    for scene, args, presets in jobs:
        if presets is not None and all((scene, p) in done for p in presets):
            continue
        if presets is None and any(s == scene for s, _ in done):
            continue
        print("robust_suite: cost on %s" % scene, file=log, flush=True)
        proc = subprocess.run([bench] + args + ["--out", cost_out,
                                                "--repeats", str(repeats)],
                              check=False)
        if proc.returncode != 0:
            failed += 1
            print("robust_suite: cost bench failed on %s (exit %d)"
                  % (scene, proc.returncode), file=log)
    return failed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/results/robust.jsonl")
    parser.add_argument("--bin_dir",
                        default=os.path.dirname(os.path.abspath(__file__)),
                        help="where the case binaries are (default: beside "
                        "this script, i.e. the py_binary's runfiles)")
    parser.add_argument("--cost_bench", default="",
                        help="robust_cost_bench binary ('' = no cost runs)")
    parser.add_argument("--cost_out", default="out/results/robust_cost.jsonl")
    parser.add_argument("--profile", default="quick")
    parser.add_argument("--manifest", default="data/manifest.json")
    parser.add_argument("--index", default="data/cache/scenes/index.json")
    parser.add_argument("--repeats", type=int, default=5,
                        help="timed rounds per cost run (both modes each)")
    parser.add_argument("--skip_suite", action="store_true")
    args = parser.parse_args(argv)
    failed = 0
    if not args.skip_suite:
        failed += run_suite(args.bin_dir, args.out)
    if args.cost_bench:
        scenes = profile_scenes(args.manifest, args.index, args.profile)
        failed += run_cost(args.cost_bench, args.cost_out, scenes,
                           repeats=args.repeats)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
