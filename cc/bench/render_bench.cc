// Render benchmark: the kd-tree's traversal variants against Embree 3 on the
// same rays, single thread and several threads, interleaved in one process.
//
//   bazel build --config=opt //cc/bench:render_bench
//   bazel-out/k8-opt/bin/cc/bench/render_bench --scenes bunny,dragon
//       --preset clipping-pruning --threads 1,2 --repeats 5 --out out/bench/render.jsonl
//
// Per scene (render_scene.h RunScene; this file holds the flags): load the
// mesh and its view (manifest camera and light, else AutoView), build the
// kd-tree once, and Embree (cc/embree/embree_tracer.h)
// at the given quality. Then, before any timing,
// validation: one render with the kd-tree recording every ray; each variant and
// Embree trace the recorded rays again (cc/render/compare.h), and a sample of
// --check_rays of them is checked against brute force (cc/kdtree/brute_force.h).
// Any kd-tree variant that differs from another, or from brute force, fails
// the run (exit 1, nothing timed). Embree's disagreements are reported (grazing
// rays differ legitimately, see compare.h).
//
// Timing: for each thread count, --repeats rounds; each round renders once
// with every tracer, in an order that rotates per round, so load from other
// processes on the machine falls on all tracers alike. Embree's device has the
// same thread count. Per tracer: every run's T_R, the median and the minimum,
// all rays per second, and first_over_this_paired, the median over rounds of
// (the first tracer's T_R / this one's) in the same round; ratios kd/Embree of
// the medians, of the minima, and paired (per round, then the median). Two
// identical trees (an --envs file that changes nothing) differed by up to 14 %
// in their medians on one scene and 4 % in the median over six: rounds of one
// process ran up to 34 % apart, so compare paired ratios over several scenes.
// One JSON line per (scene, threads) is appended to --out.
//
// The renderer's own work (camera rays, hit points, shadow-ray spawns,
// shading) is in every T_R, the same for every tracer: 11-65 ms of an 800x800
// render on the 25 standard scenes of 50k triangles or more (2026-12-05),
// 0.20-0.53 of Embree's single-ray T_R and 0.24-0.84 of its packets'. So the
// ratios of T_R understate how the tracers differ. With one thread (--replay,
// the default), two more entries, replay and replay_packet, render with
// answers recorded from kd (cc/render/replay_tracer.h) in the same rounds:
// the renderer's work alone, per mode. Each tracer's T_R less its mode's
// replay in the same round is its tracing time (trace_s_median), and
// ratio_trace_only holds, per kd-tree variant, the paired ratio of each
// Embree mode's tracing time to its own. The replay renders run without the
// traversal's memory traffic, so they are a lower bound of the renderer's
// work in a real render, and the tracing times an upper bound.
//
// The timing method is kdrt's (issue 22): before the rounds, every tracer
// renders --warmup times untimed (recorded apart as T_R_warmup_runs); the
// rounds of a thread count hold the machine-wide TimingLock
// (cc/base/timing_lock.h), so no other timed step of this project runs beside
// them, and with one thread run pinned to the quieter CPU
// (cc/base/quiet_cpu.h), while the validation, Embree's build and
// disagreement count and the warm-ups run outside it. Every record carries
// "provenance" (cc/base/provenance.h: commit, dirty, source tree, compilation
// mode, CPU, the lock) of the workspace ($BUILD_WORKSPACE_DIRECTORY, else the
// current directory) and "timing" (method, rounds, warm-ups, seconds spent
// waiting for the lock; with one thread, the CPU of the rounds and each CPU's
// probe). The record is written with nlohmann-json.
//
// Variants: "kd" (the default traversal, traversal.h), "kd_packet" (kd's
// tree, primary and shadow rays in packets of 4x4 pixels, RenderOptions::packets,
// cc/kdtree/ray_packet.h), "kd_origin" (kd, with shadow and AO rays leaving
// their origin triangle untested and searched from their end,
// RenderOptions::skip_origin; validated on every recorded secondary ray),
// "kd_packet_origin" (both: packets, and shadow rays as in kd_origin), "kd_bvh"
// (kd_origin's rays through the BVH over the tree's leaves, cc/kdtree/leaf_bvh.h),
// "kd_bvh_packet" (the same in packets), "tri_bvh" and "tri_bvh_packet" (kd_bvh's
// and kd_bvh_packet's kernels over a BVH of whole triangles, no kd-tree,
// cc/kdtree/triangle_bvh.h: what the kd-tree's leaves cost); Embree likewise as "embree" (rtcIntersect1 /
// rtcOccluded1) and "embree_packet" (rtcIntersect16 / rtcOccluded16), with
// ratios of every kd tracer to each; with --embree_robust (the default) also
// as "embree_robust" and "embree_robust_packet", Embree's scene built with
// RTC_SCENE_FLAG_ROBUST, timed in the same rounds (their ratios are in
// ratio_trace_only and for the analysis to pair from the runs). A variant NAME@TARGET runs the packet
// kernel on the given Highway target ("kd_packet_origin@AVX2": 8 lanes on an
// AVX-512 machine), validated like the others, to compare kernel widths on
// the same rays. --envs adds one
// tree per environment file (the preset with the file on top), timed with the
// kd traversal (--env_variant: as kd_packet_origin or kd_bvh) in the same rounds:
// constants are tuned on the same rays and
// under the same load, and every such tree must give kd's exact hits.
//
// --twice adds with one thread, for each traced entry (the kd-tree variants
// and Embree's modes), NAME_twice: the same tracer tracing every query twice
// in a row (twice_tracer.h), timed in the same rounds. Its pass less NAME's,
// round by round, is the second traces' time, with caches and branch
// predictors warm from the first (experiments/bench_warm.py compares both
// tracers so).
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "cc/base/provenance.h"
#include "cc/base/timing_lock.h"
#include "cc/bench/render_scene.h"
#include "cc/tools/paths.h"

ABSL_FLAG(std::string, scenes, "bunny", "Comma-separated manifest scenes (fetched).");
ABSL_FLAG(std::string, repo, "",
          "Repository root (manifest, scene index); '' = the workspace ($BUILD_WORKSPACE_DIRECTORY "
          "under bazel run, else the current directory).");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups",
          "Triangle-soup cache, relative to --repo unless absolute ('' = none).");
ABSL_FLAG(std::string, preset, "clipping-pruning", "kd-tree configuration preset.");
ABSL_FLAG(std::string, threads, "1,2", "Comma-separated thread counts.");
ABSL_FLAG(int, tile, 16, "Tile side for threads > 1 (renderer.h; 0 = whole rows).");
ABSL_FLAG(int, repeats, 5, "Timed rounds per thread count (each renders every tracer once).");
ABSL_FLAG(int, warmup, 1,
          "Untimed renders per tracer and thread count before the timed rounds (recorded as "
          "T_R_warmup_runs).");
ABSL_FLAG(int, check_rays, 300, "Recorded rays (evenly spaced) checked against brute force.");
ABSL_FLAG(std::string, variants, "kd,kd_packet,kd_origin,kd_packet_origin",
          "kd-tree variants to time: kd, kd_packet, kd_origin, kd_packet_origin, kd_bvh, "
          "kd_bvh_packet; the baseline tri_bvh, tri_bvh_packet (the same kernels over a "
          "BVH of whole triangles); NAME@TARGET "
          "runs the packet kernel on that Highway target (kd_packet_origin@AVX2; the "
          "machine's: ray_packet.h PacketKernelTargets).");
ABSL_FLAG(std::string, envs, "",
          "Comma-separated environment files (env_file.h), each applied on top of --preset to "
          "build one more tree, timed as tracer env:<file name> in the same rounds (for tuning "
          "a tree's constants on the same rays; its image must equal kd's).");
ABSL_FLAG(std::string, embree, "medium", "Embree quality: low, medium, high, or off.");
ABSL_FLAG(std::string, env_variant, "kd",
          "How the --envs trees are traced: kd, kd_packet_origin (packets of 4x4 pixels, "
          "shadow rays leaving their origin triangle), kd_bvh or kd_bvh_packet (the BVH over "
          "each tree's leaves, single rays or packets): to tune a tree for that mode.");
ABSL_FLAG(bool, embree_packets, true,
          "Also time Embree with packets of 4x4 pixels (rtcIntersect16 / rtcOccluded16) as "
          "tracer embree_packet, the bar for kd_packet.");
ABSL_FLAG(bool, embree_robust, true,
          "Also time Embree with RTC_SCENE_FLAG_ROBUST (embree_tracer.h), as embree_robust "
          "(and embree_robust_packet with --embree_packets): the peer at the accuracy our "
          "watertight test keeps; its disagreements with kd are recorded apart.");
ABSL_FLAG(bool, replay, true,
          "With one thread, also time the renderer's own work per mode: renders whose tracer "
          "replays recorded answers (replay_tracer.h), as replay and replay_packet, and each "
          "tracer's time less the replay of its mode, round by round (trace_s_median, "
          "ratio_trace_only).");
ABSL_FLAG(bool, twice, false,
          "With one thread, also time each traced tracer (kd-tree variants, Embree's modes) "
          "tracing every query twice in a row, as NAME_twice (twice_tracer.h): the second "
          "trace's time, caches and branch predictors warm from the first, is NAME_twice's "
          "less NAME's.");
ABSL_FLAG(bool, classes, false,
          "With one thread, also time each single-ray tracer on each class of the recorded "
          "rays, traced alone in a tight loop (ray_classes.h: camera rays that reach no node, "
          "that hit nothing, that hit; shadow rays), paired per round with Embree's: where "
          "the time goes by what the rays do (record: ray_classes).");
ABSL_FLAG(std::string, out, "", "JSON-lines output file (appended; '' = stdout only).");

namespace {

std::vector<std::string> List(const std::string& flag) {
  return absl::StrSplit(flag, ',', absl::SkipEmpty());
}

// The flags as RunScene's options; false on a bad --threads.
bool Options(kdtree::bench::RenderBenchOptions* o) {
  o->repo = absl::GetFlag(FLAGS_repo);
  o->cache_dir = absl::GetFlag(FLAGS_cache_dir);
  o->preset = absl::GetFlag(FLAGS_preset);
  for (const std::string& t : List(absl::GetFlag(FLAGS_threads))) {
    int threads = 0;
    if (!absl::SimpleAtoi(t, &threads) || threads < 1) return false;
    o->threads.push_back(threads);
  }
  o->tile = absl::GetFlag(FLAGS_tile);
  o->repeats = absl::GetFlag(FLAGS_repeats);
  o->warmup = absl::GetFlag(FLAGS_warmup);
  o->check_rays = absl::GetFlag(FLAGS_check_rays);
  o->variants = List(absl::GetFlag(FLAGS_variants));
  o->envs = List(absl::GetFlag(FLAGS_envs));
  o->embree = absl::GetFlag(FLAGS_embree);
  o->env_variant = absl::GetFlag(FLAGS_env_variant);
  o->embree_packets = absl::GetFlag(FLAGS_embree_packets);
  o->embree_robust = absl::GetFlag(FLAGS_embree_robust);
  o->replay = absl::GetFlag(FLAGS_replay);
  o->twice = absl::GetFlag(FLAGS_twice);
  o->classes = absl::GetFlag(FLAGS_classes);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  kdtree::bench::RenderBenchOptions options;
  if (absl::GetFlag(FLAGS_repeats) < 1 || absl::GetFlag(FLAGS_warmup) < 0 || !Options(&options)) {
    std::fprintf(stderr,
                 "render_bench: --repeats must be >= 1, --warmup >= 0 and --threads whole "
                 "numbers >= 1\n");
    return 2;
  }
  FILE* out = nullptr;
  const std::string path = kdtree::FromInvocationDir(absl::GetFlag(FLAGS_out));
  if (!path.empty()) {
    out = std::fopen(path.c_str(), "a");
    if (out == nullptr) {
      std::fprintf(stderr, "render_bench: cannot open %s\n", path.c_str());
      return 1;
    }
  }
  // Where the numbers come from; the timed rounds hold `lock`.
  kdtree::TimingLock lock;
  // Untimed work holds the lock shared, timed rounds exclusively (timing_lock.h).
  if (const absl::Status st = lock.HoldShared(); !st.ok()) {
    std::fprintf(stderr, "%s\n", std::string(st.message()).c_str());
    return 1;
  }
  kdtree::Provenance provenance = kdtree::CollectProvenance(kdtree::Workspace());
  provenance.timing_lock = lock.path();
  const kdtree::bench::RenderBenchContext ctx{&lock, provenance.ToJson()};
  int rc = 0;
  for (const std::string& scene : List(absl::GetFlag(FLAGS_scenes))) {
    const absl::Status st = kdtree::bench::RunScene(scene, options, ctx, out);
    if (!st.ok()) {
      std::fprintf(stderr, "render_bench: %s: %s\n", scene.c_str(), std::string(st.message()).c_str());
      rc = 1;
    }
  }
  if (out != nullptr && std::fclose(out) != 0) {
    std::fprintf(stderr, "render_bench: cannot write %s\n", path.c_str());
    rc = 1;
  }
  return rc;
}
