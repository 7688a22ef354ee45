#!/usr/bin/python3
"""The speed benchmarks of issues 7 and 23: build throughput and parallel speed-up, render throughput against Embree.

Runs the two optimised benchmark binaries over the fetched scenes
(data/cache/scenes/index.json) and appends their JSON lines to OUT/build.jsonl
and OUT/render.jsonl; then prints a Markdown summary of everything in OUT
(also with --summary_only, to re-read earlier runs; the tables are
experiments/bench_tables.py's and bench_structure.py's). Both binaries validate before they time:
build_bench checks seeded rays against brute force and that every timed build
writes the validated tree (its fingerprint); render_bench checks the kd-tree's
rays against brute force and records Embree's disagreements. Both benches time
alone under the machine-wide timing lock, after untimed warm-ups.

  experiments/bench.py                        # defaults below
  experiments/bench.py --build_min_tris 1000000 --render_min_tris 50000
  experiments/bench.py --repo ../other-checkout   # scenes fetched there
  experiments/bench.py --skip_build --twice --out out/warm   # first and second traces
  experiments/bench.py --skip_build --classes --out out/classes   # per class of ray

With --twice, render_bench also times every tracer tracing each query twice
in a row, and the summary adds how much of each tracer's time is first
touches (experiments/bench_warm.py). With --classes, render_bench also
times the single-ray tracers on each class of the recorded rays alone
(camera rays that reach no node, that hit nothing, that hit; shadow rays),
and the summary adds where the time goes by class
(experiments/bench_classes.py). With --processes N, each scene's
render_bench runs N times (the scenes in turn, N passes), and the summary
pools the rounds of a scene's processes (experiments/bench_merge.py): the
same paired ratio moves between processes by more than between rounds.

Provenance: every record carries the "provenance" of the binary that made it
(cc/base/provenance.h). Each summary states it (commit, dirty, compilation
mode, CPU) and refuses to summarise records of different source trees, or
timings from a binary not built for timing (bazel -c opt), unless
--allow_mixed_provenance (or, for a non-optimised build,
--allow_unoptimized_timings) is given. The benches are run from the repository
root, so their records carry this checkout's provenance.
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from analysis import provenance  # noqa: E402  (the one provenance check)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import opt_binary  # noqa: E402  (experiments/provenance.py)
import jsonl  # noqa: E402  (the results files' one reader)
import bench_tables  # noqa: E402  (the Markdown tables)
import bench_structure  # noqa: E402  (the tables of packet work and bytes)
import bench_merge  # noqa: E402  (several processes' rounds pooled, --processes)
import bench_warm  # noqa: E402  (the first and second traces, --twice)
import bench_classes  # noqa: E402  (per class of ray, --classes)

BIN = opt_binary("cc", "bench")  # the --config=opt binaries
BUILD_PRESETS = ("binning-8-driving,binning-32,clipping-pruning,"
                 "sah-packet-binned,sah-packet-binned-cp")


def scenes_from_index(index_path, min_tris, only=""):
    with open(index_path) as f:
        scenes = json.load(f)["scenes"]
    names = [s for s in only.split(",") if s] or sorted(scenes)
    return [(n, scenes[n]) for n in names
            if n in scenes and scenes[n]["triangles"] >= min_tris]


def run(cmd):
    # From the repository root: the benches take their provenance from the
    # current directory (the checkout that built them).
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)


ProvenanceError = provenance.ProvenanceError


def check_provenance(records, what, allow_mixed=False, allow_unoptimized=False):
    """The distinct provenances of the records, [(provenance, count)] in order
    first seen. The analysis's checks (analysis/provenance.py): raises
    ProvenanceError when the records come from more than one code (source
    tree and compilation mode) or CPU, or a timing from a binary not built for
    timing, unless allowed (--allow_mixed_provenance, which allows mixed CPUs
    too, and --allow_unoptimized_timings)."""
    grouped = provenance.check_one_provenance(records, allow_mixed, allow_mixed, what)
    provenance.check_timing_builds(records, allow_unoptimized, what)
    return [(prov, len(recs)) for prov, recs in grouped]


def provenance_line(provenances):
    """The sentence that states where the numbers come from."""
    if not provenances:
        return "Provenance: no records."
    if len(provenances) == 1:
        return "Provenance: %s." % provenance.short(provenances[0][0], cpu=True)
    return "Provenance, %d of them: %s." % (len(provenances), "; ".join(
        "%s (%d records)" % (provenance.short(p, cpu=True), n) for p, n in provenances))


def summarise(records, summary, what, allow_mixed=False, allow_unoptimized=False):
    """The provenance line, then the summary; ProvenanceError as
    check_provenance."""
    provenances = check_provenance(records, what, allow_mixed, allow_unoptimized)
    return provenance_line(provenances) + "\n\n" + summary(records)




def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repo", default=ROOT,
                   help="checkout whose data/ holds the fetched scenes (index, soups)")
    p.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    p.add_argument("--scenes", default="", help="comma-separated subset")
    p.add_argument("--build_min_tris", type=int, default=1000000)
    p.add_argument("--build_presets", default=BUILD_PRESETS)
    p.add_argument("--render_min_tris", type=int, default=50000)
    p.add_argument("--render_preset", default="sah-packet")
    # The kd-tree's variants, then the baseline over whole triangles
    # (cc/kdtree/triangle_bvh.h), which the table "What the kd-tree's
    # structure costs" sets beside them.
    p.add_argument("--render_variants",
                   default="kd,kd_packet,kd_origin,kd_packet_origin,kd_bvh,kd_bvh_packet,"
                           "tri_bvh,tri_bvh_packet")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--twice", action="store_true",
                   help="render_bench --twice: every tracer also traces each query twice")
    p.add_argument("--classes", action="store_true",
                   help="render_bench --classes: each class of ray traced alone per tracer")
    p.add_argument("--processes", type=int, default=1,
                   help="render_bench processes per scene, their rounds pooled in the summary")
    p.add_argument("--skip_build", action="store_true")
    p.add_argument("--skip_render", action="store_true")
    p.add_argument("--summary_only", action="store_true")
    p.add_argument("--allow_mixed_provenance", action="store_true",
                   help="summarise records of different source trees, or timed with a "
                        "binary not built for timing (each is stated)")
    p.add_argument("--allow_unoptimized_timings", action="store_true",
                   help="summarise timings from a binary not built for timing")
    a = p.parse_args(argv)
    a.repo, a.out = os.path.abspath(a.repo), os.path.abspath(a.out)
    index = os.path.join(a.repo, "data", "cache", "scenes", "index.json")
    cache_dir = os.path.join(a.repo, "data", "cache", "soups")
    os.makedirs(a.out, exist_ok=True)
    build_out = os.path.join(a.out, "build.jsonl")
    render_out = os.path.join(a.out, "render.jsonl")
    if not a.summary_only:
        if not a.skip_build:
            for name, s in scenes_from_index(index, a.build_min_tris, a.scenes):
                run([os.path.join(BIN, "build_bench"), "--mesh", os.path.join(a.repo, s["file"]),
                     "--name", name, "--cache_dir", cache_dir, "--presets", a.build_presets,
                     "--threads", "1,2", "--repeats", str(a.repeats), "--out", build_out])
        if not a.skip_render:
            scenes = scenes_from_index(index, a.render_min_tris, a.scenes)
            for _pass in range(a.processes):  # the scenes in turn, once per pass
                for name, _scene in scenes:
                    run([os.path.join(BIN, "render_bench"), "--repo", a.repo, "--scenes", name,
                         "--cache_dir", cache_dir, "--preset", a.render_preset,
                         "--threads", "1,2", "--repeats", str(a.repeats),
                         "--variants", a.render_variants,
                         "--out", render_out] + (["--twice"] if a.twice else [])
                        + (["--classes"] if a.classes else []))
    try:
        build_records, raw_render = jsonl.read(build_out), jsonl.read(render_out)
    except ValueError as e:  # a line that is not a record, named with its file and line
        sys.exit("bench.py: %s" % e)
    try:
        allow = (a.allow_mixed_provenance, a.allow_unoptimized_timings)
        build = summarise(build_records, bench_tables.build_summary, build_out, *allow)
        render_records = bench_merge.merge_processes(raw_render)
        render = summarise(render_records, bench_tables.render_summary, render_out, *allow)
        targets = summarise(render_records, bench_tables.targets_summary, render_out, *allow)
        robust = summarise(render_records, lambda r: bench_tables.targets_summary(r, robust=True),
                           render_out, *allow)
        passes = summarise(render_records, bench_tables.passes_summary, render_out, *allow)
        packets = summarise(render_records, bench_structure.packets_summary, render_out, *allow)
        # Records before 2026-12-06 have no Embree bytes: no table then.
        memory_table = bench_structure.memory_summary(render_records)
        memory = (summarise(render_records, lambda _: memory_table, render_out, *allow)
                  if memory_table else "")
        warm = summarise(render_records, bench_warm.warm_summary, render_out, *allow)
        tri_table = bench_structure.triangle_bvh_summary(render_records)
        tri = (summarise(render_records, lambda _: tri_table, render_out, *allow)
               if tri_table else "")
        classes_table = bench_classes.classes_summary(render_records)
        classes = (summarise(render_records, lambda _: classes_table, render_out, *allow)
                   if classes_table else "")
    except ProvenanceError as e:
        sys.exit("bench.py: %s" % e)
    print("## Build (build_bench)\n")
    print(build)
    print("\n## Render (render_bench)\n")
    for line in (bench_merge.processes_line(render_records), bench_merge.probe_line(raw_render)):
        if line:
            print(line + "\n")
    print(render)
    print("\n## Issue 23's targets (render_bench, one thread, paired per round)\n")
    print(targets)
    print("\n## The same against Embree built with RTC_SCENE_FLAG_ROBUST (same rounds)\n")
    print(robust)
    print("\n## Per pass, tracing alone (render_bench, one thread, paired per round)\n")
    print(passes)
    print("\n## The packet kernel's work (render_bench's packet_counts, one render)\n")
    print(packets)
    if memory:
        print("\n## Memory: the tree against Embree's BVH (render_bench, bytes per triangle)\n")
        print(memory)
    if tri:
        print("\n## What the kd-tree's structure costs: the same kernels over a BVH of whole "
              "triangles (render_bench tri_bvh, one thread, paired per round)\n")
        print(tri)
    if any(n.endswith("_twice") for r in render_records for n in r.get("tracers", {})):
        print("\n## First and second traces (render_bench --twice, one thread, paired per "
              "round)\n")
        print(warm)
    if classes:
        print("\n## Per class of ray, single rays traced alone (render_bench --classes, one "
              "thread, paired per round)\n")
        print(classes)


if __name__ == "__main__":
    main()
