#!/bin/bash
# build_bench and render_bench end to end on a small generated scene: one
# record per preset (build) and per thread count (render), written through
# nlohmann-json, each with "provenance" and "timing"; the warm-ups recorded
# apart from the timed runs; the timed steps wait for the timing lock while
# another process holds it.
set -euo pipefail
BIN="$TEST_SRCDIR/$TEST_WORKSPACE/cc/bench"
T="$TEST_TMPDIR"
cd "$T"
# Timed steps hold this lock (cc/base/timing_lock.h), not the machine's.
export KDTREE_TIMING_LOCK="$T/timing.lock"
# Not a checkout: the commit comes from here (cc/base/provenance.h).
export KDTREE_GIT_COMMIT=0123456789abcdef0123456789abcdef01234567

# A closed octahedron above a ground quad.
mkdir -p repo/data/cache/scenes
cp "$TEST_SRCDIR/$TEST_WORKSPACE/cc/tools/testdata/octahedron.obj" repo/scene.obj
cat > repo/data/cache/scenes/index.json <<'JSON'
{"scenes": {"tiny": {"file": "scene.obj", "triangles": 10}}}
JSON

# Another process holds the lock for a moment: the bench waits (its untimed
# work holds the lock shared, its timed builds exclusively: neither runs
# beside another process's timed step).
/usr/bin/python3 - "$KDTREE_TIMING_LOCK" <<'PY' &
import fcntl, sys, time
with open(sys.argv[1], "a") as f:
    fcntl.flock(f, fcntl.LOCK_EX)
    open(sys.argv[1] + ".held", "w").close()
    time.sleep(1.5)
PY
holder=$!
while [ ! -e "$KDTREE_TIMING_LOCK.held" ]; do sleep 0.05; done
start_ns=$(date +%s%N)
"$BIN/build_bench" --mesh=repo/scene.obj --name=tiny --cache_dir= \
  --presets=binning-32,clipping-pruning --threads=1,2 --repeats=3 --warmup=2 --out=build.jsonl \
  2> build.err
waited_ms=$(( ($(date +%s%N) - start_ns) / 1000000 ))
wait "$holder"
if [ "$waited_ms" -lt 1000 ]; then echo "FAIL: build_bench did not wait for the held lock ($waited_ms ms)"; exit 1; fi

# Under `bazel run`: the scene index and the provenance come from the
# workspace, a relative --out from where it was invoked.
mkdir -p elsewhere
BUILD_WORKSPACE_DIRECTORY="$T/repo" BUILD_WORKING_DIRECTORY="$T/elsewhere" \
  "$BIN/render_bench" --scenes=tiny --cache_dir= --preset=clipping-pruning --threads=1,2 \
  --repeats=2 --warmup=1 --variants=kd,kd_packet --embree=medium --out=render.jsonl \
  > render.stdout
# A tree with an environment file on top, traced with packets (--env_variant).
printf 'KDTree {\n    traversalCost 30\n}\n' > kt30.env
"$BIN/render_bench" --repo=repo --scenes=tiny --cache_dir= --preset=sah-packet --threads=1 \
  --repeats=1 --warmup=0 --variants=kd_packet_origin --envs=kt30.env --env_variant=kd_packet_origin \
  --embree=off --out=env.jsonl > /dev/null
# The baseline BVH over whole triangles, single rays and packets.
"$BIN/render_bench" --repo=repo --scenes=tiny --cache_dir= --preset=sah-packet --threads=1 \
  --repeats=1 --warmup=0 --variants=kd_bvh_packet,tri_bvh,tri_bvh_packet --embree=off \
  --out=tri.jsonl > /dev/null
# Every tracer also tracing each query twice (--twice), and the single-ray tracers per
# class of ray (--classes), with one thread only.
"$BIN/render_bench" --repo=repo --scenes=tiny --cache_dir= --preset=sah-packet --threads=1,2 \
  --repeats=1 --warmup=0 --variants=kd_origin,kd_bvh --embree=medium --embree_packets=false \
  --embree_robust=false --twice --classes --out=twice.jsonl > /dev/null
if "$BIN/render_bench" --repo=repo --scenes=tiny --cache_dir= --repeats=0 > /dev/null 2> err.txt; then
  echo "--repeats=0 accepted"; exit 1
fi

/usr/bin/python3 - <<'PY'
import json
def check(cond, msg):
    if not cond:
        raise SystemExit("FAIL: " + msg)
def check_provenance(rec, what):
    prov = rec.get("provenance")
    check(isinstance(prov, dict), what + ": no provenance")
    for k in ["commit", "dirty", "source_tree", "compilation_mode", "optimized", "ndebug",
              "timing_build", "compiler", "cpu_model", "cpu_id", "cpu_caches", "cores", "timing_lock", "timed_beside"]:
        check(k in prov, "%s: provenance has no %s" % (what, k))
    check(prov["commit"] == "0123456789abcdef0123456789abcdef01234567", what + ": commit")
    check(prov["timing_lock"].endswith("timing.lock") and prov["timed_beside"] == 0,
          what + ": timed alone under the lock")
    check(prov["compilation_mode"] in ("opt", "fastbuild", "dbg"), what + ": mode")
    check(prov["cores"] >= 1, what + ": cores")

build = [json.loads(l) for l in open("build.jsonl")]
check(len(build) == 4, "one build record per preset and thread count")
check([(r["preset"], r["threads"]) for r in build] ==
      [("binning-32", 1), ("binning-32", 2), ("clipping-pruning", 1), ("clipping-pruning", 2)],
      "build records in order")
for r in build:
    for k in ["scene", "mesh", "n_tri", "preset", "threads", "T_B", "T_B_runs", "T_B_warmup_runs",
              "mtri_per_s", "checked_rays", "tree_fingerprint", "stats", "timing", "provenance"]:
        check(k in r, "build record has no " + k)
    check("optimized" not in r, "build: the build mode is in provenance only")
    check(r["scene"] == "tiny" and r["n_tri"] == 10, "build: scene")
    check(len(r["T_B_runs"]) == 3 and len(r["T_B_warmup_runs"]) == 2, "build: runs apart")
    check(sorted(r["T_B_runs"])[1] == r["T_B"], "build: the median")
    check(len(r["tree_fingerprint"]) == 16, "build: fingerprint")
    check(r["stats"]["N_TP"] > 0 and "N_I" in r["stats"], "build: stats")
    check(r["timing"]["rounds"] == 3 and r["timing"]["warmup"] == 2, "build: timing")
    check_provenance(r, "build")
check(build[0]["tree_fingerprint"] == build[1]["tree_fingerprint"], "1 and 2 threads: one tree")

render = [json.loads(l) for l in open("elsewhere/render.jsonl")]
stdout = [json.loads(l) for l in open("render.stdout")]
check(render == stdout, "render: the same records on stdout and in --out")
check([r["threads"] for r in render] == [1, 2], "one render record per thread count")
for r in render:
    for k in ["bench", "scene", "n_tri", "preset", "threads", "tile", "repeats", "rays", "primary",
              "shadow", "ao", "camera_hits", "camera_triangles", "shadow_occluded",
              "leaf_layout_bytes", "tree_bytes", "embree_bvh_bytes", "tracers",
              "ratio_kd_over_embree", "ratio_kd_over_embree_packet", "ratio_trace_only",
              "embree_native_ray16", "packet_counts", "validation", "timing", "provenance"]:
        check(k in r, "render record has no " + k)
    # What the camera sees (render_check.h CameraCoverage): the tiny scene
    # is in view, so some rays hit it, on at most all of its 10 triangles.
    check(0 < r["camera_hits"] <= r["primary"], "render: camera hits")
    check(0 < r["camera_triangles"] <= min(r["n_tri"], r["camera_hits"]),
          "render: camera triangles")
    check(0 <= r["shadow_occluded"] <= r["shadow"], "render: occluded shadow rays")
    # Memory: the tree is its nodes and its leaf packets; Embree's BVH some
    # bytes a triangle.
    check(r["tree_bytes"] > r["leaf_layout_bytes"] > 0, "render: tree bytes")
    check(r["embree_bvh_bytes"] > 0, "render: Embree's bytes")
    # The packet variant's counting render: primary rays (closest hit) and
    # shadow rays (any hit), each lane counting as its single ray.
    counts = r["packet_counts"]
    check(list(counts) == ["kd_packet"], "render: packet counts of the packet variant only")
    closest, any_hit = counts["kd_packet"]["closest"], counts["kd_packet"]["any"]
    check(closest["rays"] == r["primary"] and any_hit["rays"] == r["shadow"] + r["ao"],
          "render: packet counts of every primary and secondary ray")
    check(0 < closest["packets"] <= -(-r["primary"] // 16), "render: packets reaching the tree")
    check(closest["inner_steps"] <= closest["lane_inner_visits"] <= 16 * closest["inner_steps"],
          "render: lanes per inner step")
    check(abs(closest["per_ray"]["N_TR"] * closest["rays"] - closest["lane_inner_visits"]) < 1e-6,
          "render: N_TR per ray")
    check(r["bench"] == "render" and r["scene"] == "tiny" and r["n_tri"] == 10, "render: scene")
    traced = ["kd", "kd_packet", "embree", "embree_packet", "embree_robust",
              "embree_robust_packet"]
    replays = ["replay", "replay_packet"] if r["threads"] == 1 else []
    check(list(r["tracers"]) == traced + replays, "render: tracers (replays with one thread)")
    if replays:
        t = r["tracers"]
        for name in traced:
            replay = t["replay_packet" if name.endswith("packet") else "replay"]["T_R_runs"]
            less = sorted(a - b for a, b in zip(t[name]["T_R_runs"], replay))
            check(abs(t[name]["trace_s_median"] - sum(less) / 2) < 1e-12,
                  "render: %s's tracing time, its mode's replay subtracted per round" % name)
        check(set(r["ratio_trace_only"]) == {"kd", "kd_packet"} and
              set(r["ratio_trace_only"]["kd"]) == set(traced[2:]),
              "render: tracing-time ratios")
    else:
        check(r["ratio_trace_only"] == {}, "render: no replays with two threads")
    for name, t in r["tracers"].items():
        check(len(t["T_R_runs"]) == 2 and len(t["T_R_warmup_runs"]) == 1,
              "render: %s runs apart" % name)
        check(t["T_R_min"] == min(t["T_R_runs"]), "render: min")
    kd, em = r["tracers"]["kd"], r["tracers"]["embree"]
    paired = sorted(e / k for e, k in zip(em["T_R_runs"], kd["T_R_runs"]))
    check(abs(r["ratio_kd_over_embree"]["kd"]["paired"] - sum(paired) / 2) < 1e-12,
          "render: paired per round")
    check(set(r["ratio_kd_over_embree_packet"]) == {"kd", "kd_packet"}, "render: packet ratios")
    v = r["validation"]
    check(v["brute_force_mismatches"] == 0 and v["brute_force_checked"] > 0, "render: brute force")
    check(v["variants_vs_kd_mismatches"] == {"kd": 0, "kd_packet": 0}, "render: variants")
    check(isinstance(v["embree_disagreements"], dict), "render: Embree disagreements")
    check(isinstance(v["embree_robust_disagreements"], dict),
          "render: Embree's (RTC_SCENE_FLAG_ROBUST) disagreements")
    check(r["timing"]["rounds"] == 2 and r["timing"]["warmup"] == 1, "render: timing")
    check_provenance(r, "render")
env = [json.loads(l) for l in open("env.jsonl")]
check(len(env) == 1 and list(env[0]["tracers"]) == ["kd_packet_origin", "env:kt30.env", "replay",
                                                     "replay_packet"],
      "env: the preset's tree and the environment file's, then the replays")
check("trace_s_median" in env[0]["tracers"]["env:kt30.env"], "env: a tracing time")
check(env[0]["validation"]["variants_vs_kd_mismatches"] == {"kd_packet_origin": 0,
                                                             "env:kt30.env": 0}, "env: variants")
check(env[0]["tri_bvh_bytes"] is None, "env: no triangle BVH unless traced")
tri = [json.loads(l) for l in open("tri.jsonl")]
check(len(tri) == 1 and tri[0]["validation"]["variants_vs_kd_mismatches"] ==
      {"kd_bvh_packet": 0, "tri_bvh": 0, "tri_bvh_packet": 0}, "tri_bvh: the kd-tree's answers")
check(tri[0]["tri_bvh_bytes"] > 0 and tri[0]["tri_bvh_build_s"] >= 0,
      "tri_bvh: its bytes and build")
check(sorted(tri[0]["packet_counts"]) == ["kd_bvh_packet", "tri_bvh_packet"]
      and tri[0]["packet_counts"]["tri_bvh_packet"]["closest"]["rays"] > 0,
      "tri_bvh_packet: what its packets did")
twice = [json.loads(l) for l in open("twice.jsonl")]
check([list(r["tracers"]) for r in twice] ==
      [["kd_origin", "kd_bvh", "embree", "kd_origin_twice", "kd_bvh_twice", "embree_twice",
        "replay", "replay_packet"],
       ["kd_origin", "kd_bvh", "embree"]], "twice: each traced tracer again, with one thread")
check(twice[0]["validation"]["variants_vs_kd_mismatches"] == {"kd_origin": 0, "kd_bvh": 0},
      "kd_bvh: the kd-tree's answers")
check(twice[0]["bvh_bytes"] > 0 and twice[0]["bvh_build_s"] >= 0, "kd_bvh: its bytes and build")
check(twice[0]["bvh_packet_bytes"] >= twice[0]["leaf_layout_bytes"], "kd_bvh: its own leaf packets")
classes = twice[0]["ray_classes"]["classes"]
check("shadow" in classes and all(list(c["ns_runs"]) == ["kd_origin", "kd_bvh", "embree"]
                                  and list(c["embree_over"]) == ["kd_origin", "kd_bvh"]
                                  for c in classes.values()),
      "classes: the single-ray tracers, not the twice ones, paired with Embree's")
check(twice[1]["ray_classes"] is None, "classes: one thread only")
print("ok")
PY
grep -q "repeats" err.txt
