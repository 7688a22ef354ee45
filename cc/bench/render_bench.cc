// Render benchmark: the kd-tree's traversal variants against Embree 3 on the
// same rays, single thread and several threads, interleaved in one process.
//
//   bazel build --config=opt //cc/bench:render_bench
//   bazel-out/k8-opt/bin/cc/bench/render_bench --scenes bunny,dragon
//       --preset clipping-pruning --threads 1,2 --repeats 5 --out out/bench/render.jsonl
//
// Per scene: load the mesh and its view (manifest camera and light, else
// AutoView), build the kd-tree once, and Embree (cc/embree/embree_tracer.h)
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
// (kd_origin's rays through the BVH over the tree's leaves, cc/kdtree/leaf_bvh.h); Embree likewise as "embree" (rtcIntersect1 /
// rtcOccluded1) and "embree_packet" (rtcIntersect16 / rtcOccluded16), with
// ratios of every kd tracer to each; with --embree_robust (the default) also
// as "embree_robust" and "embree_robust_packet", Embree's scene built with
// RTC_SCENE_FLAG_ROBUST, timed in the same rounds (their ratios are in
// ratio_trace_only and for the analysis to pair from the runs). A variant NAME@TARGET runs the packet
// kernel on the given Highway target ("kd_packet_origin@AVX2": 8 lanes on an
// AVX-512 machine), validated like the others, to compare kernel widths on
// the same rays. --envs adds one
// tree per environment file (the preset with the file on top), timed with the
// kd traversal (--env_packets: as kd_packet_origin) in the same rounds:
// constants are tuned on the same rays and
// under the same load, and every such tree must give kd's exact hits.
//
// --twice adds with one thread, for each traced entry (the kd-tree variants
// and Embree's modes), NAME_twice: the same tracer tracing every query twice
// in a row (twice_tracer.h), timed in the same rounds. Its pass less NAME's,
// round by round, is the second traces' time, with caches and branch
// predictors warm from the first (experiments/bench_warm.py compares both
// tracers so).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "cc/base/json_line.h"
#include "cc/base/provenance.h"
#include "cc/base/quiet_cpu.h"
#include "cc/base/timing_lock.h"
#include "cc/bench/bench_record.h"
#include "cc/bench/packet_counts.h"
#include "cc/bench/ray_classes.h"
#include "cc/bench/render_check.h"
#include "cc/bench/render_times.h"
#include "cc/bench/render_variants.h"
#include "cc/bench/twice_tracer.h"
#include "cc/embree/embree_tracer.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/render/framing.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/manifest.h"
#include "cc/render/renderer.h"
#include "cc/render/replay_tracer.h"
#include "cc/render/view.h"
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
          "kd-tree variants to time: kd, kd_packet, kd_origin, kd_packet_origin, kd_bvh; NAME@TARGET "
          "runs the packet kernel on that Highway target (kd_packet_origin@AVX2; the "
          "machine's: ray_packet.h PacketKernelTargets).");
ABSL_FLAG(std::string, envs, "",
          "Comma-separated environment files (env_file.h), each applied on top of --preset to "
          "build one more tree, timed as tracer env:<file name> in the same rounds (for tuning "
          "a tree's constants on the same rays; its image must equal kd's).");
ABSL_FLAG(std::string, embree, "medium", "Embree quality: low, medium, high, or off.");
ABSL_FLAG(bool, env_packets, false,
          "Trace the --envs trees as kd_packet_origin (packets of 4x4 pixels, shadow rays "
          "leaving their origin triangle) instead of as kd: to tune a tree for the packet "
          "kernel.");
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

namespace kdtree {
namespace {

using bench::Entry;

// The run's shared context: where its numbers come from, and the lock its
// timed rounds hold.
struct Context {
  TimingLock* lock;
  bench::Json provenance;
};

absl::Status RunScene(const std::string& scene, const Context& ctx, FILE* out) {
  using bench::Json;
  const std::string repo =
      absl::GetFlag(FLAGS_repo).empty() ? Workspace()
                                        : FromInvocationDir(absl::GetFlag(FLAGS_repo));
  absl::StatusOr<SceneRef> ref = ResolveScene(repo, scene);
  if (!ref.ok()) return ref.status();
  const std::string cache = absl::GetFlag(FLAGS_cache_dir);
  // Relative to --repo; an absolute directory as given (experiments/bench.py
  // passes one: joined to the repository, it made a second cache under
  // <repo>/<its own path>).
  const std::string cache_dir =
      cache.empty() || cache[0] == '/' ? cache : absl::StrCat(repo, "/", cache);
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(ref->mesh_path, cache_dir);
  if (!soup.ok()) return soup.status();
  const View view = ref->has_view ? ref->view : AutoView(soup->Bounds());
  absl::StatusOr<Config> config = Preset(absl::GetFlag(FLAGS_preset));
  if (!config.ok()) return config.status();
  std::vector<std::string> envs;
  for (absl::string_view path :
       absl::StrSplit(absl::GetFlag(FLAGS_envs), ',', absl::SkipEmpty())) {
    envs.push_back(FromInvocationDir(std::string(path)));
  }
  absl::StatusOr<std::unique_ptr<bench::SceneTrees>> trees =
      bench::BuildSceneTrees(*soup, *config, envs);
  if (!trees.ok()) return trees.status();
  const KdTree* tree = &(*trees)->tree;
  const KdTreeTracer& kd = *(*trees)->kd;
  const BruteForce bf(*soup);
  absl::StatusOr<std::vector<Entry>> proto =
      bench::VariantEntries(**trees, absl::StrSplit(absl::GetFlag(FLAGS_variants), ','),
                            absl::GetFlag(FLAGS_env_packets));
  if (!proto.ok()) return proto.status();

  // Validation (untimed).
  RenderOptions ropt;
  ropt.cast_shadow_rays = config->cast_shadow_rays;
  RenderOptions rec_opt = ropt;
  rec_opt.record_rays = true;
  const RenderResult recorded = Render(*soup, kd, view, rec_opt);
  Json variant_json = Json::object();
  for (const Entry& e : *proto) {
    uint64_t bad = 0;
    if (absl::Status st = bench::CheckVariant(scene, *soup, view, ropt, recorded, e, &bad); !st.ok()) {
      return st;
    }
    variant_json[e.name] = bad;
  }
  // What the packet kernel does (untimed): the kd-tree's packet variants.
  Json packet_counts = Json::object();
  for (const Entry& e : *proto) {
    if (!e.packets || e.tracer != &kd) continue;
    absl::StatusOr<Json> counts = bench::CountPackets(*soup, *tree, view, ropt, e);
    if (!counts.ok()) return counts.status();
    packet_counts[e.name] = *std::move(counts);
  }
  uint64_t checked = 0;
  const uint64_t bf_bad =
      bench::BruteForceMismatches(recorded.rays, bf, absl::GetFlag(FLAGS_check_rays), &checked);
  if (bf_bad != 0) return absl::InternalError(absl::StrCat(scene, ": ", bf_bad, " rays differ from brute force"));

  const std::string quality_flag = absl::GetFlag(FLAGS_embree);
  const bool use_embree = quality_flag != "off";
  for (absl::string_view ts : absl::StrSplit(absl::GetFlag(FLAGS_threads), ',')) {
    int threads = 0;
    if (!absl::SimpleAtoi(ts, &threads) || threads < 1) return absl::InvalidArgumentError("--threads");
    std::vector<std::unique_ptr<EmbreeTracer>> embrees;  // default flags, then ROBUST
    Json disagree = nullptr, disagree_robust = nullptr;
    std::vector<Entry> entries = *proto;
    if (use_embree) {
      absl::StatusOr<EmbreeQuality> q = ParseEmbreeQuality(quality_flag);
      if (!q.ok()) return q.status();
      EmbreeOptions eo;
      eo.quality = *q;
      eo.threads = threads;
      for (const bool robust : {false, true}) {
        if (robust && !absl::GetFlag(FLAGS_embree_robust)) break;
        eo.robust = robust;
        absl::StatusOr<std::unique_ptr<EmbreeTracer>> e = bench::AddEmbree(
            *soup, eo, robust ? "embree_robust" : "embree", absl::GetFlag(FLAGS_embree_packets),
            recorded.rays, kd, &entries, robust ? &disagree_robust : &disagree);
        if (!e.ok()) return e.status();
        embrees.push_back(*std::move(e));
      }
    }
    // Each traced entry again, tracing every query twice (--twice).
    std::vector<std::unique_ptr<bench::TwiceTracer>> twice;
    if (absl::GetFlag(FLAGS_twice) && threads == 1) {
      for (size_t k = 0, n = entries.size(); k < n; ++k) {
        twice.push_back(std::make_unique<bench::TwiceTracer>(entries[k].tracer));
        Entry e = entries[k];
        e.name = absl::StrCat(e.name, "_twice");
        e.tracer = twice.back().get();
        entries.push_back(std::move(e));
      }
    }
    const auto is_embree = [&](const Entry& e) {
      const auto* w = dynamic_cast<const bench::TwiceTracer*>(e.tracer);
      const Tracer* tracer = w != nullptr ? &w->inner() : e.tracer;
      return std::any_of(embrees.begin(), embrees.end(),
                         [&](const auto& t) { return t.get() == tracer; });
    };
    const size_t n_kd = proto->size();  // entries[0, n_kd) are kd-trees
    const size_t n_traced = entries.size();  // then Embree's, the twice, then the replays
    std::vector<std::unique_ptr<ReplayTracer>> replays;
    if (absl::GetFlag(FLAGS_replay) && threads == 1) {
      for (const bool packets : {false, true}) {
        replays.push_back(std::make_unique<ReplayTracer>(kd));
        entries.emplace_back(packets ? "replay_packet" : "replay", replays.back().get(), packets,
                             true);
        entries.back().replay = replays.back().get();
      }
    }
    RenderOptions topt = ropt;
    topt.threads = threads;
    topt.tile_size = absl::GetFlag(FLAGS_tile);
    const auto options_of = [&](const Entry& e) {
      RenderOptions o = topt;
      o.packets = e.packets;
      o.skip_origin = e.skip_origin;
      return o;
    };
    // One render of entry e; kd-tree variants must reproduce the validated
    // image exactly (Embree may differ on grazing rays: its disagreements are
    // reported above).
    const auto render = [&](const Entry& e) -> absl::StatusOr<RenderResult> {
      std::optional<ScopedPacketKernelTarget> kernel;
      if (!e.kernel.empty()) kernel.emplace(e.kernel);  // checked in validation
      if (e.replay != nullptr) e.replay->Rewind();
      RenderResult r = Render(*soup, *e.tracer, view, options_of(e));
      if (!is_embree(e) && r.rgb != recorded.rgb) {
        return absl::InternalError(absl::StrCat(e.name, ": image differs"));
      }
      if (e.replay != nullptr && e.replay->overran()) {
        return absl::InternalError(absl::StrCat(e.name, ": more queries than recorded"));
      }
      return r;
    };
    // The replays' answers: one render of kd in their mode, recorded.
    for (Entry& e : entries) {
      if (e.replay == nullptr) continue;
      e.replay->Record();
      if (Render(*soup, *e.tracer, view, options_of(e)).rgb != recorded.rgb) {
        return absl::InternalError(absl::StrCat(e.name, ": recorded image differs"));
      }
    }
    // Warm-ups, untimed and outside the lock.
    const int warmup = absl::GetFlag(FLAGS_warmup);
    for (int w = 0; w < warmup; ++w) {
      for (Entry& e : entries) {
        absl::StatusOr<RenderResult> r = render(e);
        if (!r.ok()) return r.status();
        e.warmup.push_back(r->seconds);
      }
    }
    // Timed rounds, alone under the lock.
    const int repeats = absl::GetFlag(FLAGS_repeats);
    const double waited_before = ctx.lock->waited_seconds();
    if (absl::Status st = ctx.lock->Acquire(); !st.ok()) return st;
    // One thread: the rounds on the quieter CPU (quiet_cpu.h).
    std::optional<ScopedQuietCpu> quiet;
    if (threads == 1) quiet.emplace();
    for (int round = 0; round < repeats; ++round) {
      for (size_t k = 0; k < entries.size(); ++k) {
        Entry& e = entries[(k + round) % entries.size()];
        absl::StatusOr<RenderResult> r = render(e);
        if (!r.ok()) {
          ctx.lock->Release();
          return r.status();
        }
        e.runs.push_back(r->seconds);
        e.primary.push_back(r->primary.seconds);
        e.secondary.push_back(r->shadow.seconds + r->ao.seconds);
        e.rays = r->total_rays();
      }
    }
    // Per class of ray, the single-ray tracers alone (--classes).
    Json ray_classes;
    if (absl::GetFlag(FLAGS_classes) && threads == 1) {
      std::vector<bench::RenderVariant> single;
      for (size_t k = 0; k < n_traced; ++k) {
        const Entry& e = entries[k];
        if (!e.packets && dynamic_cast<const bench::TwiceTracer*>(e.tracer) == nullptr) {
          single.push_back(e);
        }
      }
      ray_classes = bench::TimeRayClasses(bench::ClassifyRays(recorded.rays, *tree), single,
                                          "embree", warmup, repeats);
    }
    const Json cpu = QuietCpuJson(quiet ? &*quiet : nullptr);
    quiet.reset();
    ctx.lock->Release();
    const double lock_wait_s = ctx.lock->waited_seconds() - waited_before;
    Json tracers = bench::TracerTimes(entries);
    // Ratios of each kd-tree tracer to Embree's single rays and, when timed,
    // to its packets; with the replays, of the tracing times alone too.
    Json ratios = Json::object(), packet_ratios = Json::object(), trace_only = Json::object();
    for (size_t k = n_kd; k < n_traced; ++k) {
      if (entries[k].name == "embree") ratios = bench::RatiosTo(entries, n_kd, entries[k]);
      if (entries[k].name == "embree_packet") {
        packet_ratios = bench::RatiosTo(entries, n_kd, entries[k]);
      }
    }
    if (!replays.empty()) trace_only = bench::TraceOnly(entries, n_kd, n_traced, &tracers);
    const bench::CameraCoverage coverage = bench::CameraCoverageOf(recorded.primary_hits);
    Json rec = {{"bench", "render"},
                {"scene", scene},
                {"n_tri", soup->size()},
                {"preset", absl::GetFlag(FLAGS_preset)},
                {"threads", threads},
                {"tile", topt.tile_size},
                {"repeats", repeats},
                {"rays", recorded.total_rays()},
                {"primary", recorded.primary.rays},
                {"shadow", recorded.shadow.rays},
                {"ao", recorded.ao.rays},
                // What the camera sees (render_check.h CameraCoverage), and
                // how many shadow rays are occluded.
                {"camera_hits", coverage.hits},
                {"camera_triangles", coverage.triangles},
                {"shadow_occluded", recorded.s_hit},
                // The leaf packets' bytes (before 4c5d23d, also a second
                // node array of 8 bytes a node).
                {"leaf_layout_bytes", LeafLayoutBytes(*tree)},
                // The whole tree (its nodes too) and Embree's BVH (its
                // memory monitor, embree_tracer.h bvh_bytes), null without
                // Embree.
                {"tree_bytes", TreeBytes(*tree)},
                {"embree_bvh_bytes", embrees.empty() ? Json() : Json(embrees[0]->bvh_bytes())},
                // kd_bvh's nodes (its leaves are the tree's) and their build.
                {"bvh_bytes", (*trees)->bvh->bvh().bytes()},
                {"bvh_build_s", (*trees)->bvh_build_seconds},
                {"tracers", std::move(tracers)},
                {"ratio_kd_over_embree", std::move(ratios)},
                {"ratio_kd_over_embree_packet", std::move(packet_ratios)},
                {"ratio_trace_only", std::move(trace_only)},
                {"embree_native_ray16", !embrees.empty() && embrees[0]->native_ray16()},
                {"packet_counts", packet_counts},
                {"ray_classes", std::move(ray_classes)}};
    rec["validation"] = {{"variants_vs_kd_mismatches", variant_json},
                         {"brute_force_checked", checked},
                         {"brute_force_mismatches", bf_bad},
                         {"embree_disagreements", disagree},
                         {"embree_robust_disagreements", disagree_robust}};
    rec["timing"] = {{"method", "warm-up excluded; then rounds rendering every tracer once, in an "
                                "order rotating per round, alone under the timing lock (one "
                                "thread: on the quieter CPU); ratios paired per round"},
                     {"rounds", repeats},
                     {"warmup", warmup},
                     {"lock_wait_s", lock_wait_s},
                     // With one thread, the CPU the rounds ran on and each
                     // CPU's probe (quiet_cpu.h, ms); null otherwise.
                     {"cpu", cpu["cpu"]},
                     {"cpu_probe_ms", cpu["cpu_probe_ms"]}};
    rec["provenance"] = ctx.provenance;
    const std::string line = JsonLine(rec);
    if (!bench::WriteLine(stdout, line) || !bench::WriteLine(out, line)) {
      return absl::InternalError("cannot write the record");
    }
  }
  return absl::OkStatus();
}

}  // namespace
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  if (absl::GetFlag(FLAGS_repeats) < 1 || absl::GetFlag(FLAGS_warmup) < 0) {
    std::fprintf(stderr, "render_bench: --repeats must be >= 1 and --warmup >= 0\n");
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
  const kdtree::Context ctx{&lock, provenance.ToJson()};
  int rc = 0;
  for (const std::string& scene :
       std::vector<std::string>(absl::StrSplit(absl::GetFlag(FLAGS_scenes), ','))) {
    const absl::Status st = kdtree::RunScene(scene, ctx, out);
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
