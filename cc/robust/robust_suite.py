"""Runs the adversarial suite and the robustness cost bench for the report.

Issue "Hard cases stay numerically stable": every kd-tree preset against
brute force on rays built to break traversal and intersection (Woop, Benthin
& Wald 2013 watertight test; Ize 2013 conservative traversal), and what the
watertight test costs against the fast one (Moeller & Trumbore 1997) on the
same rays.

    P="--out out/results/robust.jsonl --cost_out out/results/robust_cost.jsonl --profile quick"
    T=$(/usr/bin/python3 cc/robust/robust_suite.py $P --print_targets)
    [ -z "$T" ] || bazel build --config=opt $T
    /usr/bin/python3 cc/robust/robust_suite.py $P \\
        --bin_dir "$(bazel info --config=opt bazel-bin)/cc/robust" --compilation_mode opt

(run from the repository root; experiments/reproduce.sh does this). Nothing
is rebuilt or rerun that the results already hold for the same code:

Suite: each hard case is a gtest binary of cc/robust/BUILD (CASES below; run
without a filter, so every scene of a parametrised case runs) that checks
every preset against brute force and prints its numbers as `ROBUST_JSON {...}`
lines. Every such record is written to --out with "hard_case" (1-9),
"binary" and "provenance" added, then one {"kind": "binary", ...} record per
binary with its exit status ("passed": the gtest assertions, 0 mismatches,
held), and last one {"kind": "suite", ...} record: the profile, whether every
case ran and passed, its ray stride and the provenance. --ray_stride k
(quick reproductions) has every check keep every k-th packet of 16 of its
case's rays (KDTREE_ROBUST_RAY_STRIDE, cc/robust/preset_check.h): every
preset, mode and scene still runs, on 1/k of the rays; bazel test and the
default of 1 check them all. --out is replaced only when all of
it ran (a failing case is recorded, not fatal). The binaries are untimed
checks: --jobs of them run at once. When --out already holds a complete,
passing run of the same source tree (cc/base/source_id.sh: the tools'
sources, uncommitted edits included) and profile, the suite is skipped.

Cost (with --cost_bench): robust_cost_bench on every scene of --profile
(data/manifest.json) that data/fetch.py fetched (data/cache/scenes/index.json),
preset "default", plus the generated scene with every preset ("default", then
experiments/matrix.json's variants and beyond_variants). Appended to
--cost_out; a (scene, preset) already there from the same source tree, from a
timing build, with at least --repeats rounds, is not rerun. The bench runs
after the suite, never beside it (its rounds are timed).

"provenance" of the suite's records (the C++ case binaries do not collect it):
commit, dirty and source_tree of the checkout (experiments/provenance.py's
code_identity), compilation_mode (--compilation_mode,
else guessed from --bin_dir's bazel-out/<cpu>-<mode>/ path), the machine as
the C++ records name it (experiments/provenance.py's machine(): cpu_model,
cpu_id, cpu_caches, cores), timestamp_utc and collected_by.
"""

import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import time

try:  # under bazel (the package path) or as a script (its directory first)
    from cc.robust import robust_cost_runs as cost
except ImportError:
    import robust_cost_runs as cost

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
SUITE_TARGET = "//cc/robust:robust_suite"  # builds every case binary
COST_TARGET = "//cc/robust:robust_cost_bench"


# --- provenance --------------------------------------------------------------

# experiments/provenance.py (robust_cost_runs.load_experiments_module).
PROVENANCE = cost.load_experiments_module("provenance")


def code_identity(repo_root="."):
    """{"commit", "dirty", "source_tree"} of the checkout at repo_root, by
    experiments/provenance.py (it honours the identity reproduce.sh pinned,
    $KDTREE_SOURCE_ID); None values when unknown."""
    return dict(PROVENANCE.code_identity(os.path.abspath(repo_root)))


def guess_compilation_mode(bin_dir):
    """"opt", "fastbuild" or "dbg" from a bazel-out/<cpu>-<mode>/bin path;
    "unknown" otherwise."""
    m = re.search(r"(?:^|/)bazel-out/[^/]*?-(opt|fastbuild|dbg)(?:-[^/]*)?/",
                  os.path.abspath(bin_dir) + "/")
    return m.group(1) if m else "unknown"


def suite_provenance(identity, compilation_mode):
    """The provenance the suite's records carry (see the module doc)."""
    return {"commit": identity.get("commit"),
            "dirty": bool(identity.get("dirty")),
            "source_tree": identity.get("source_tree"),
            "compilation_mode": compilation_mode,
            **PROVENANCE.machine(),
            "timestamp_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ",
                                           time.gmtime()),
            "collected_by": "cc/robust/robust_suite.py"}


def source_tree_of(rec):
    prov = rec.get("provenance")
    return prov.get("source_tree") if isinstance(prov, dict) else None


# --- suite -------------------------------------------------------------------

def parse_records(stdout):
    """The ROBUST_JSON records of a binary's output, in order."""
    out = []
    for line in stdout.splitlines():
        if line.startswith(PREFIX):
            out.append(json.loads(line[len(PREFIX):]))
    return out


def suite_done(out_path, source_tree, profile, cases=None, ray_stride=1):
    """The suite record of out_path when it is a complete, passing run of
    source_tree (not None), profile and ray_stride, with a passing binary
    record for every case; else None."""
    cases = CASES if cases is None else cases
    if not source_tree:
        return None
    recs = cost.read_records(out_path)
    suites = [r for r in recs if r.get("kind") == "suite"]
    if not suites:
        return None
    suite = suites[-1]
    if not (suite.get("complete") and suite.get("passed")
            and suite.get("profile") == profile
            and suite.get("ray_stride", 1) == ray_stride
            and source_tree_of(suite) == source_tree):
        return None
    passed = {r.get("hard_case") for r in recs
              if r.get("kind") == "binary" and r.get("passed")
              and source_tree_of(r) == source_tree}
    if not all(number in passed for number, _, _ in cases):
        return None
    return suite


def _run_case(bin_dir, case, ray_stride=1):
    number, binary, _ = case
    env = dict(os.environ, KDTREE_ROBUST_RAY_STRIDE=str(ray_stride))
    start = time.time()
    proc = subprocess.run([os.path.join(bin_dir, binary)],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, check=False, env=env)
    return proc, time.time() - start


def run_suite(bin_dir, out_path, cases=None, log=None, provenance=None,
              profile=None, jobs=1, ray_stride=1):
    """Runs every case binary (jobs at a time); writes --out; returns the
    number that failed."""
    cases = CASES if cases is None else cases
    log = log or sys.stderr
    provenance = provenance or {}
    start = time.time()
    for number, binary, what in cases:
        print("robust_suite: case %d (%s): %s" % (number, what, binary),
              file=log, flush=True)
    # Longest first (by the last run's times in out_path), so that no long
    # case starts last; the records keep the cases' order.
    last = {r.get("binary"): r.get("seconds") or 0 for r in cost.read_records(out_path)
            if r.get("kind") == "binary"}
    order = sorted(range(len(cases)), key=lambda i: -last.get(cases[i][1], 0))
    with concurrent.futures.ThreadPoolExecutor(max(1, jobs)) as pool:
        futures = {pool.submit(_run_case, bin_dir, cases[i], ray_stride): i
                   for i in order}
        done = {}
        for fut in concurrent.futures.as_completed(futures):
            i = futures[fut]
            done[i] = fut.result()
            proc, seconds = done[i]
            number, binary, _ = cases[i]
            passed = proc.returncode == 0
            print("robust_suite:   case %d %s, %s, %.1f s"
                  % (number, binary,
                     "passed" if passed else "FAILED (exit %d)"
                     % proc.returncode, seconds), file=log, flush=True)
            if not passed:
                print(proc.stdout[-4000:], file=log)
    records, failed = [], 0
    for i, (number, binary, what) in enumerate(cases):
        proc, seconds = done[i]
        found = parse_records(proc.stdout)
        for rec in found:
            rec["hard_case"] = number
            rec["binary"] = binary
            rec["provenance"] = provenance
        records.extend(found)
        passed = proc.returncode == 0
        failed += not passed
        records.append({"kind": "binary", "hard_case": number,
                        "binary": binary, "what": what, "passed": passed,
                        "exit_code": proc.returncode, "records": len(found),
                        "seconds": round(seconds, 3),
                        "provenance": provenance})
    records.append({"kind": "suite", "profile": profile, "complete": True,
                    "passed": failed == 0, "cases": len(cases),
                    "failed": failed, "jobs": max(1, jobs),
                    "ray_stride": ray_stride,
                    "seconds": round(time.time() - start, 3),
                    "provenance": provenance})
    os.makedirs(os.path.dirname(os.path.abspath(out_path)), exist_ok=True)
    tmp = out_path + ".new"
    with open(tmp, "w", encoding="utf-8") as f:
        for rec in records:
            f.write(json.dumps(rec, sort_keys=True) + "\n")
    os.replace(tmp, out_path)
    return failed


# --- plan and main -----------------------------------------------------------

def presets_for_generated(args):
    """The generated scene's presets: --matrix's, else the bench's own list
    (robust_cost_bench --list_presets)."""
    if os.path.exists(args.matrix):
        return cost.generated_presets(args.matrix)
    if args.cost_bench:
        return cost.list_presets(args.cost_bench)
    raise ValueError("%s not found: pass --matrix, or --cost_bench to ask the "
                     "bench for its presets" % args.matrix)


def plan(args, identity, log=None):
    """(run the suite?, [(scene, presets)] cost runs to do), with a line on
    log for what is skipped and why."""
    log = log or sys.stderr
    tree = identity.get("source_tree")
    if not tree:
        print("robust_suite: the source tree is unknown (not a git "
              "checkout?): nothing counts as done", file=log)
    suite = None if args.skip_suite else suite_done(
        args.out, tree, args.profile, ray_stride=args.ray_stride)
    if suite is not None:
        print("robust_suite: %s already holds a complete, passing suite run "
              "of source tree %s (profile %s, commit %s, %s): not rebuilt or "
              "rerun" % (args.out, cost.short_tree(tree), args.profile,
                         (identity.get("commit") or "unknown")[:12],
                         (suite.get("provenance") or {}).get("timestamp_utc")),
              file=log, flush=True)
    run = not args.skip_suite and suite is None
    jobs = []
    if args.cost:
        scenes = cost.profile_scenes(args.manifest, args.index, args.profile)
        jobs = cost.cost_jobs(scenes, presets_for_generated(args),
                              cost.done_runs(args.cost_out, tree, args.repeats))
        if not jobs:
            print("robust_suite: %s already holds every cost run of profile "
                  "%s (%d scenes + %s) of source tree %s with >= %d rounds: "
                  "not rebuilt or rerun" % (args.cost_out, args.profile,
                                            len(scenes), cost.GENERATED,
                                            cost.short_tree(tree), args.repeats),
                  file=log, flush=True)
    return run, jobs


def main(argv=None, identity=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/results/robust.jsonl")
    parser.add_argument("--bin_dir",
                        default=os.path.dirname(os.path.abspath(__file__)),
                        help="where the case binaries are (default: beside "
                        "this script, i.e. the py_binary's runfiles)")
    parser.add_argument("--cost_bench", default="",
                        help="robust_cost_bench binary ('' = no cost runs; "
                        "with --print_targets: see --cost)")
    parser.add_argument("--cost", action="store_true",
                        help="with --print_targets: plan the cost runs too")
    parser.add_argument("--cost_out", default="out/results/robust_cost.jsonl")
    parser.add_argument("--profile", default="quick")
    parser.add_argument("--manifest", default="data/manifest.json")
    parser.add_argument("--index", default="data/cache/scenes/index.json")
    parser.add_argument("--matrix", default="experiments/matrix.json",
                        help="the presets of the generated scene")
    parser.add_argument("--repeats", type=int, default=5,
                        help="timed rounds per cost run (both tests each)")
    parser.add_argument("--jobs", type=int, default=1,
                        help="case binaries run at once (untimed checks)")
    parser.add_argument("--repo_root", default=".",
                        help="the checkout whose code identity is recorded")
    parser.add_argument("--compilation_mode", default="",
                        help="how the binaries were built (default: from "
                        "--bin_dir's bazel-out path)")
    parser.add_argument("--ray_stride", type=int, default=1,
                        help="check every k-th packet of 16 rays of each "
                        "case (quick reproductions; default: every ray)")
    parser.add_argument("--skip_suite", action="store_true")
    parser.add_argument("--print_targets", action="store_true",
                        help="print the Bazel targets still needed (none "
                        "when the results hold everything) and exit")
    args = parser.parse_args(argv)
    if args.ray_stride < 1:
        parser.error("--ray_stride must be >= 1")
    args.cost = args.cost or bool(args.cost_bench)
    if identity is None:
        identity = code_identity(args.repo_root)
    run, jobs = plan(args, identity)
    if args.print_targets:
        targets = ([SUITE_TARGET] if run else []) + ([COST_TARGET] if jobs
                                                     else [])
        print(" ".join(targets))
        return 0
    failed = 0
    if run:
        mode = args.compilation_mode or guess_compilation_mode(args.bin_dir)
        failed += run_suite(args.bin_dir, args.out,
                            provenance=suite_provenance(identity, mode),
                            profile=args.profile, jobs=args.jobs,
                            ray_stride=args.ray_stride)
    if args.cost_bench and jobs:
        scenes = cost.profile_scenes(args.manifest, args.index, args.profile)
        failed += cost.run_cost(args.cost_bench, args.cost_out, scenes,
                                repeats=args.repeats,
                                presets_generated=presets_for_generated(args),
                                source_tree=identity.get("source_tree"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
