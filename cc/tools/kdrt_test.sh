#!/bin/bash
# kdrt end to end on a small generated OBJ: the PNG and the JSON record (every
# record valid against cc/tools/kdrt_record.schema.json), the zero-shadow-ray
# rule for a lightless view, the ray dump, thread determinism, the Embree
# comparison and the fast render (--fast_render).
set -euo pipefail
RUNFILES="$TEST_SRCDIR/$TEST_WORKSPACE"
KDRT="$RUNFILES/cc/tools/kdrt"
T="$TEST_TMPDIR"
cd "$T"
# Timed steps hold this lock (cc/base/timing_lock.h), not the machine's.
export KDTREE_TIMING_LOCK="$T/timing.lock"

# A closed octahedron above a ground quad.
cp "$TEST_SRCDIR/$TEST_WORKSPACE/cc/tools/testdata/octahedron.obj" scene.obj
cat > lit.view <<'VIEW'
camera { position 0.5 2 6 look_at 0 -0.5 0 fov 45 }
resolution 64 48
light { position -3 6 3 }
VIEW
cat > dark.view <<'VIEW'
camera { position 0.5 2 6 look_at 0 -0.5 0 }
resolution 64 48
VIEW

"$KDRT" --mesh=scene.obj --view=lit.view --image=out/scene_clipping-pruning.png --record=out/results.jsonl \
  --repeats=2 --cache_dir= --dump_rays=rays.bin --embree=medium > lit.json
"$KDRT" --mesh=scene.obj --view=dark.view --image=out/scene_median-24-8.png \
  --record=out/results.jsonl --repeats=1 --cache_dir= \
  --preset=median-24-8 > dark.json
"$KDRT" --mesh=scene.obj --view=lit.view --image=out2/x.png --repeats=1 --cache_dir= --threads=2 \
  --max_leaf_size=1 > lit2.json
"$KDRT" --mesh=scene.obj --view=lit.view --repeats=1 --cache_dir= --threads=1 \
  --max_leaf_size=1 --fast_render > lit1.json
# The fast mode with Embree's rounds: its packets, its robust setting and
# the baseline over whole triangles too.
"$KDRT" --mesh=scene.obj --view=lit.view --repeats=2 --cache_dir= --fast_render \
  --embree=medium --triangle_bvh > fastemb.json
if "$KDRT" --mesh=scene.obj --view=lit.view --repeats=1 --cache_dir= --triangle_bvh \
    > /dev/null 2> notri.err; then
  echo "FAIL: --triangle_bvh without --fast_render was accepted"; exit 1
fi
grep -q -- "--triangle_bvh needs --fast_render" notri.err
"$KDRT" --mesh=scene.obj --view=dark.view --repeats=1 --cache_dir= --fast_render \
  --embree=medium > fastdark.json
# A budget of ~0 s: every timed step runs once although --repeats=4.
"$KDRT" --mesh=scene.obj --view=lit.view --repeats=4 --repeat_budget_s=1e-12 --cache_dir= \
  --embree=medium > budget.json
# Triangles left out at load are counted in the record by reason; the mesh
# arrives through a process substitution (a pipe, read once).
{ cat scene.obj; printf 'v 1e31 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n';
  printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\nf -3 -2 -1\n'; } > dropped.obj
"$KDRT" --mesh=<(cat dropped.obj) --view=lit.view --repeats=1 --cache_dir=data/cache/soups \
  > dropped.json
if "$KDRT" --mesh=scene.obj --preset=bogus --cache_dir= > /dev/null 2> err.txt; then
  echo "bad preset accepted"; exit 1
fi
grep -q "bogus" err.txt

test -s out/scene_clipping-pruning.png
test -s out/scene_median-24-8.png
test -s out2/x.png  # its directory made by kdrt
test "$(wc -l < out/results.jsonl)" -eq 2
# 32 + 56 n + 8 bytes
size=$(stat -c %s rays.bin)
test $(( (size - 40) % 56 )) -eq 0

# Every record printed or appended: kdrt's fields of the schema, each
# required one with its type, and no other (analysis/record_schema.py).
/usr/bin/python3 "$RUNFILES/analysis/record_schema.py" \
  --schema "$RUNFILES/cc/tools/kdrt_record.schema.json" --sections kdrt \
  lit.json dark.json lit2.json lit1.json budget.json dropped.json fastemb.json fastdark.json \
  out/results.jsonl
/usr/bin/python3 -c 'import json; r = json.load(open("lit.json")); r["surprise"] = 1
print(json.dumps(r))' > undeclared.json
if /usr/bin/python3 "$RUNFILES/analysis/record_schema.py" \
    --schema "$RUNFILES/cc/tools/kdrt_record.schema.json" undeclared.json 2> /dev/null; then
  echo "the validator accepted an undeclared field"; exit 1
fi

/usr/bin/python3 - <<'PY'
import json
lit = json.load(open("lit.json"))
dark = json.load(open("dark.json"))
one = json.load(open("lit1.json"))
budget = json.load(open("budget.json"))
two = json.load(open("lit2.json"))
def check(cond, msg):
    if not cond:
        raise SystemExit("FAIL: " + msg)
check(lit["scene"] == "scene" and lit["n_tri"] == 10, "scene / n_tri")
none = {"nonfinite": 0, "degenerate": 0, "point_line_faces": 0}
check(lit["dropped_at_load"] == none, "nothing dropped")
dropped = json.load(open("dropped.json"))
check(dropped["n_tri"] == 10 and dropped["dropped_at_load"] == dict(none, nonfinite=1, degenerate=1),
      "dropped triangles counted by reason")
check(len(lit["T_B_runs"]) == 2 and len(lit["T_R_runs"]) == 2, "runs")
check(lit["P_hit"] + lit["P_miss"] == 64 * 48, "primary count")
check(lit["S_hit"] + lit["S_miss"] == lit["P_hit"], "one shadow ray per hit")
check(lit["S_hit"] > 0 and lit["S_miss"] > 0, "shadow and light")
check(abs(lit["perf_krays"] - 64 * 48 / lit["T_R"] / 1000) < 1e-6 * lit["perf_krays"], "perf")
check(lit["effects"]["shadow"]["rays"] == lit["P_hit"], "shadow rays")
check(lit["embree"]["P_hit"] == lit["P_hit"], "embree P_hit")
check(lit["disagreements"]["other"] == 0, "embree disagreements")
check(lit["counting_mismatches"] == 0, "counting pass")
check(lit["traversal"]["primary"]["rays"] == 64 * 48, "counted rays")
check(dark["lights"] == 0 and dark["S_hit"] + dark["S_miss"] == 0, "no light, no shadow rays")
check(dark["effects"]["shadow"]["rays"] == 0, "no shadow rays")
check(dark["embree"] is None and dark["preset"] == "median-24-8", "dark record")
check(one["image_fnv64"] == two["image_fnv64"], "1 and 2 threads give the same image")
check(one["S_hit"] == two["S_hit"] and one["N_IT"] == two["N_IT"], "1 and 2 threads counts")
check(one["label"] == "clipping-pruning+custom" and one["config"]["max_leaf_size"] == 1, "override")
check(budget["repeats"] == 4 and budget["repeat_budget_s"] == 1e-12, "budget recorded")
check(len(budget["T_B_runs"]) == 1 and len(budget["T_R_runs"]) == 1, "budget: one kd-tree run each")
check(len(budget["embree"]["T_B_runs"]) == 1 and len(budget["embree"]["T_R_runs"]) == 1,
      "budget: one Embree run each")
check(lit["embree"]["paired_ratio_runs"] == [e / k for e, k in
      zip(lit["embree"]["T_R_runs"], lit["T_R_runs"])], "paired per round")
check(len(lit["embree"]["paired_ratio_runs"]) == 2, "two rounds, the warm-up apart")
check(lit["perf_ratio_kd_over_embree"] == lit["embree"]["paired_ratio"], "the paired median")
check(lit["T_B_warmup"] > 0 and lit["embree"]["T_R_warmup"] > 0, "warm-ups recorded")
check(lit["embree"]["bvh_bytes"] > 16 * lit["n_tri"], "Embree's BVH bytes recorded")
prov = lit["provenance"]
check(prov["timing_lock"].endswith("timing.lock") and prov["timed_beside"] == 0, "timed alone")
check(prov["cores"] >= 1 and prov["compilation_mode"] in ("opt", "fastbuild", "dbg"), "build")
check(lit["repeat_budget_s"] == 0, "no budget by default")
check(lit["fast_render"] is None, "no fast render by default")
fast = one["fast_render"]
check(len(fast["T_R_runs"]) == 1 and fast["T_R"] > 0 and fast["primary_s"] > 0
      and fast["shadow_s"] > 0, "fast render timed")
fe = json.load(open("fastemb.json"))
f, rob = fe["fast_render"], fe["fast_render"]["embree_robust"]
check(len(f["embree_packets"]["T_R_runs"]) == 2 and len(rob["packets_T_R_runs"]) == 2,
      "Embree's packets and its robust setting timed in the same two rounds")
so = f["single_origin"]
check(len(so["T_R_runs"]) == 2 and so["T_R"] > 0 and so["shadow_s"] > 0,
      "our other single-ray mode timed in the same two rounds")
sb = f["single_bvh"]
check(len(sb["T_R_runs"]) == 2 and sb["T_R"] > 0 and sb["build_s"] >= 0,
      "the BVH over the leaves timed in the same two rounds, its build recorded")
pb = f["packets_bvh"]
check(len(pb["T_R_runs"]) == 2 and pb["T_R"] > 0 and pb["build_s"] == sb["build_s"],
      "packets through the BVH timed in the same two rounds")
check(sb["bytes"] > 0 and sb["bytes"] % 256 == 0 and pb["bytes"] == sb["bytes"],
      "the BVH's nodes' bytes recorded")
check(sb["packet_bytes"] >= 160 and sb["packet_bytes"] % 160 == 0
      and pb["packet_bytes"] == sb["packet_bytes"], "the BVH's own leaf packets' bytes recorded")
check(f["single_paired_ratio_runs"] == [e / min(k, s, b) for e, k, s, b in
      zip(fe["embree"]["T_R_runs"], fe["T_R_runs"], so["T_R_runs"], sb["T_R_runs"])],
      "single rays: Embree's over the fastest of ours, paired per round")
check(f["best_paired_ratio_runs"] == [min(e, p) / min(k, s, b, q, v) for e, p, k, s, b, q, v in
      zip(fe["embree"]["T_R_runs"], f["embree_packets"]["T_R_runs"], fe["T_R_runs"],
          so["T_R_runs"], sb["T_R_runs"], f["T_R_runs"], pb["T_R_runs"])],
      "best mode: the fastest of each side, per round")
tb = f["triangle_bvh"]
check(len(tb["single"]["T_R_runs"]) == 2 and len(tb["packets"]["T_R_runs"]) == 2
      and tb["build_s"] > 0 and tb["bytes"] > 0,
      "the baseline over whole triangles timed in the same two rounds, its build and bytes")
check(tb["best_paired_ratio_runs"] == [min(e, p) / min(s, q) for e, p, s, q in
      zip(fe["embree"]["T_R_runs"], f["embree_packets"]["T_R_runs"], tb["single"]["T_R_runs"],
          tb["packets"]["T_R_runs"])]
      and tb["single_paired_ratio_runs"] == [e / s for e, s in
      zip(fe["embree"]["T_R_runs"], tb["single"]["T_R_runs"])],
      "the baseline against Embree, paired per round")
check("triangle_bvh" not in fast, "no baseline unless asked for")
check(rob["single_paired_ratio_runs"] == [e / min(k, s, b) for e, k, s, b in
      zip(rob["T_R_runs"], fe["T_R_runs"], so["T_R_runs"], sb["T_R_runs"])],
      "robust Embree against the fastest of our single rays, paired per round")
check(rob["best_paired_ratio_runs"] == [min(e, p) / min(k, s, b, q, v) for e, p, k, s, b, q, v in
      zip(rob["T_R_runs"], rob["packets_T_R_runs"], fe["T_R_runs"], so["T_R_runs"],
          sb["T_R_runs"], f["T_R_runs"], pb["T_R_runs"])],
      "best mode against best mode, per round")
check(rob["wrong"]["primary"] == 0 and rob["disagreements"] >= 0, "robust Embree's answers")
check(0 <= rob["disagreements_at_origin"] <= rob["disagreements"],
      "robust Embree's disagreements at a ray's origin")
ps = f["passes"]
check(all(len(ps[k]) == 2 for k in ("replay_primary_s_runs", "replay_shadow_s_runs",
                                     "replay_packets_primary_s_runs",
                                     "replay_packets_shadow_s_runs")),
      "the replays timed in the same two rounds")
def fastest(lanes, replay):
    # Per round, the fastest positive tracing time (lane less replay); 0: none.
    out = []
    for i, r in enumerate(replay):
        t = [lane[i] - r for lane in lanes if lane[i] - r > 0]
        out.append(min(t) if t else 0.0)
    return out
def ratios(theirs, ours):
    return [a / b for a, b in zip(theirs, ours) if a > 0 and b > 0]
for key, p in (("primary", "camera"), ("shadow", "shadow")):
    emb, kd = fe["embree"]["effects"][key]["seconds_runs"], fe["effects"][key]["seconds_runs"]
    single = ratios(fastest([emb], ps["replay_%s_s_runs" % key]),
                    fastest([kd, so[key + "_s_runs"], sb[key + "_s_runs"]],
                            ps["replay_%s_s_runs" % key]))
    packets = ratios(fastest([f["embree_packets"][key + "_s_runs"]],
                             ps["replay_packets_%s_s_runs" % key]),
                     fastest([f[key + "_s_runs"], pb[key + "_s_runs"]],
                             ps["replay_packets_%s_s_runs" % key]))
    for name, want in ((p + "_single", single), (p + "_packets", packets)):
        runs = ps[name]["paired_ratio_runs"]
        # On this tiny scene a pass's tracing time may be within the
        # replay's noise: such rounds give no ratio.
        check(len(runs) == len(want) <= 2
              and all(abs(a - b) <= 1e-12 * abs(b) for a, b in zip(runs, want))
              and (ps[name]["paired_ratio"] is None) == (not runs),
              name + ": each lane's pass less its replay, Embree's over ours per round")
dark_passes = json.load(open("fastdark.json"))["fast_render"]["passes"]
check(all(dark_passes[n] == {"paired_ratio": None, "paired_ratio_runs": []}
          for n in ("shadow_single", "shadow_packets")), "no light: no shadow-pass ratio")
print("ok")
PY
