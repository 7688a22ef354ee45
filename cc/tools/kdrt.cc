// kdrt: builds the kd-tree for one scene and configuration, renders it, and
// records the report's measurements (tables 1-10) as one JSON line.
//
//   bazel build --config=opt //cc/tools:kdrt
//   "$(bazel info --config=opt bazel-bin)"/cc/tools/kdrt --scene=bunny --preset=clipping-pruning
//       --repeats=3 --embree=medium --image=/tmp/bunny.png --record=/tmp/kdrt.jsonl
//
// Steps (timing method: timed_render.h; timed steps alone under the
// machine-wide TimingLock, cc/base/timing_lock.h). Untimed, with the lock
// shared: load the mesh (through the soup cache); build the kd-tree and, with
// --embree, Embree once (T_B_warmup); render the frame recording every ray
// (the kd-tree's render warm-up, T_R_warmup), replay the rays with the
// counting traversal for N_IT / N_TR (traversal_counts.h) and with Embree
// for disagreements (compare.h; Embree's warm-up); optionally dump the rays.
// Then timed, alone under the lock: `repeats` rounds of renders alternating
// the tracers (the kd-tree; with --fast_render the renderer's packets with
// origin skipping and the same origin skipping one ray at a time, held to the
// same image; Embree) on the warm trees (T_R =
// median; Embree's time over the kd-tree's, per round, then the median:
// perf_ratio_kd_over_embree), then `repeats` rounds of builds (T_B = median);
// --repeat_budget_s caps the rounds, at least one. With --noembree_rounds
// Embree is built once, untimed, only for the comparison. The record carries
// the provenance of its numbers (cc/base/provenance.h). Prints the record on
// stdout (one JSON line), writes the image to --image and appends the record
// to --record when given. Exit code 1 on any error.
//
// perf_krays = 640,000 / T_R / 1000 in the report's sense: primary rays per
// second of render time although T_R includes the shadow rays
// (width * height in place of 640,000); all_rays_per_s counts every ray.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "cc/base/json_line.h"
#include "cc/base/median.h"
#include "cc/base/provenance.h"
#include "cc/base/timing_lock.h"
#include "cc/embree/embree_tracer.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/stats.h"
#include "cc/render/compare.h"
#include "cc/render/framing.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/manifest.h"
#include "cc/render/png.h"
#include "cc/render/ray_dump.h"
#include "cc/render/renderer.h"
#include "cc/render/cost_image.h"
#include "cc/render/traversal_counts.h"
#include "cc/render/view.h"
#include "cc/tools/kdrt_config.h"
#include "cc/tools/kdrt_lanes.h"
#include "cc/tools/kdrt_limits.h"
#include "cc/tools/kdrt_record.h"
#include "cc/tools/paths.h"
#include "cc/tools/progress.h"
#include "cc/tools/timed_build.h"
#include "cc/tools/timed_render.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, scene, "", "Scene name from data/manifest.json (mesh via data/cache/scenes/index.json).");
ABSL_FLAG(std::string, mesh, "", "Mesh file (anything assimp reads); with --scene, replaces its mesh.");
ABSL_FLAG(std::string, view, "", "View file (cc/render/view.h); default: the manifest's camera and light, else AutoView.");
ABSL_FLAG(std::string, preset, "clipping-pruning", "Configuration preset (the report's columns); '' = Config defaults.");
ABSL_FLAG(std::string, env, "", "Environment file applied on top of the preset.");
ABSL_FLAG(std::string, max_depth, "", "Override maxDepth ('' = not set).");
ABSL_FLAG(std::string, max_leaf_size, "", "Override maxLeafSize.");
ABSL_FLAG(std::string, bins, "", "Override Binning.bins.");
ABSL_FLAG(std::string, binning, "", "Override Binning.useBinning (on/off).");
ABSL_FLAG(std::string, driving_axis, "", "Override Binning.useDrivingAxis (on/off).");
ABSL_FLAG(std::string, clipping, "", "Override useClipping (on/off).");
ABSL_FLAG(std::string, pruning, "", "Override usePruning (on/off).");
ABSL_FLAG(std::string, shadows, "", "Override RTCore.castShadowRays (on/off).");
ABSL_FLAG(std::string, seed_compatible, "", "Override the seed-compatible mode (on/off).");
ABSL_FLAG(std::string, label, "", "Name of the configuration in file names and records (default: derived).");
ABSL_FLAG(std::string, image, "", "Write the rendered image here (PNG; '' = none).");
ABSL_FLAG(std::string, record, "", "Also append the record (one JSON line) to this file ('' = stdout only).");
ABSL_FLAG(int, threads, 1, "Render threads (1 = no TBB); also Embree's device threads.");
ABSL_FLAG(int, repeats, 5, "Builds and renders per tracer; medians are reported.");
ABSL_FLAG(double, repeat_budget_s, 0,
          "Stop repeating a timed build or render once its runs took this many seconds in all "
          "(at least one run; 0 = always --repeats runs). Every run is recorded.");
ABSL_FLAG(std::string, cost_image, "", "Write per-pixel N_TR / N_IT per ray kind here (cost_image.h; .npy.gz).");
ABSL_FLAG(std::string, dump_rays, "", "Write every ray and its kd-tree result here (cc/render/ray_dump.h).");
ABSL_FLAG(std::string, embree, "off", "off | low | medium | high: also build and render with Embree.");
ABSL_FLAG(bool, embree_rounds, true,
          "With --embree: also time Embree's builds and renders in the rounds, paired with the "
          "kd-tree's (false: Embree is built once, untimed, only to compare every ray).");
ABSL_FLAG(bool, embree_robust, true,
          "With --embree, its timed rounds and --fast_render: also build Embree with "
          "RTC_SCENE_FLAG_ROBUST (untimed) and time its single rays and packets in the same "
          "rounds (record fast_render.embree_robust, with the rays it answers wrongly).");
ABSL_FLAG(bool, fast_render, false,
          "Also time the renderer's fastest mode (primary and shadow rays in packets of 4x4 "
          "pixels, shadow rays leaving their origin triangle untested and searched from the "
          "light), and those shadow rays one at a time (our other single-ray mode): record "
          "field fast_render, held to the timed image.");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups", "Triangle-soup cache directory ('' = none).");
ABSL_FLAG(double, memory_budget_gb, 0,
          "Memory a run may use before it is refused (GB; 0 = half of physical memory).");
ABSL_FLAG(uint64_t, max_mesh_bytes, kdtree::kMeshInputBudget,
          "Largest mesh file, or inflated .gz, to read (cc/io/mesh_input.h); larger ones are refused.");

namespace kdtree {
namespace {

std::string MeshStem(const std::string& path) {
  std::string base = path.substr(path.find_last_of('/') + 1);
  if (base.size() > 3 && base.substr(base.size() - 3) == ".gz") base.resize(base.size() - 3);
  const size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

using Json = nlohmann::ordered_json;

// Creates the file's directory, then writes it with `write`.
absl::Status WriteFile(const std::string& path, const std::function<absl::Status(const std::string&)>& write) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) return absl::InternalError(absl::StrCat(dir.string(), ": cannot create directory: ", ec.message()));
  return write(path);
}

// --scene and --mesh: the mesh to load, the scene's name (the mesh's stem
// without --scene) and the manifest's view when it has one (view_source
// "manifest"; else view_source stays empty).
absl::Status ResolveSceneFlags(std::string* scene, std::string* mesh, View* view, std::string* view_source) {
  if (!scene->empty() && mesh->empty()) {
    absl::StatusOr<SceneRef> ref = ResolveScene(Workspace(), *scene);
    if (!ref.ok()) return ref.status();
    *mesh = ref->mesh_path;
    if (ref->has_view) {
      *view = ref->view;
      *view_source = "manifest";
    }
  } else if (!scene->empty()) {
    absl::StatusOr<bool> has = LoadManifestView(Workspace(), *scene, view);
    if (!has.ok()) return has.status();
    if (*has) *view_source = "manifest";
  } else if (!mesh->empty()) {
    *scene = MeshStem(*mesh);
  } else {
    return absl::InvalidArgumentError("give --scene or --mesh");
  }
  return absl::OkStatus();
}

// The configuration flags, for kdrt_config.h's ResolveConfig.
ConfigFlags ConfigFlagsFromCommandLine() {
  ConfigFlags cf;
  cf.preset = absl::GetFlag(FLAGS_preset);
  cf.env = FromInvocationDir(absl::GetFlag(FLAGS_env));
  cf.max_depth = absl::GetFlag(FLAGS_max_depth);
  cf.max_leaf_size = absl::GetFlag(FLAGS_max_leaf_size);
  cf.bins = absl::GetFlag(FLAGS_bins);
  cf.binning = absl::GetFlag(FLAGS_binning);
  cf.driving_axis = absl::GetFlag(FLAGS_driving_axis);
  cf.clipping = absl::GetFlag(FLAGS_clipping);
  cf.pruning = absl::GetFlag(FLAGS_pruning);
  cf.shadows = absl::GetFlag(FLAGS_shadows);
  cf.seed_compatible = absl::GetFlag(FLAGS_seed_compatible);
  cf.label = absl::GetFlag(FLAGS_label);
  return cf;
}

// Appends one line to the file at `path`.
absl::Status AppendLine(const std::string& path, const std::string& line) {
  FILE* f = std::fopen(path.c_str(), "a");
  const bool written = f != nullptr && std::fprintf(f, "%s\n", line.c_str()) >= 0;
  if (f != nullptr && std::fclose(f) == 0 && written) return absl::OkStatus();
  return absl::InternalError(absl::StrCat(path, ": cannot append the record"));
}

absl::Status Run() {
  const int repeats = absl::GetFlag(FLAGS_repeats), threads = absl::GetFlag(FLAGS_threads);
  if (repeats < 1 || threads < 1) return absl::InvalidArgumentError("--repeats and --threads must be >= 1");
  const double budget_s = absl::GetFlag(FLAGS_repeat_budget_s);
  std::string scene = absl::GetFlag(FLAGS_scene), mesh = FromInvocationDir(absl::GetFlag(FLAGS_mesh));
  View view;
  std::string view_source;
  if (absl::Status st = ResolveSceneFlags(&scene, &mesh, &view, &view_source); !st.ok()) return st;
  absl::StatusOr<ResolvedConfig> rc = ResolveConfig(ConfigFlagsFromCommandLine());
  if (!rc.ok()) return rc.status();
  const std::string embree_flag = absl::GetFlag(FLAGS_embree);
  absl::StatusOr<EmbreeQuality> quality = ParseEmbreeQuality(embree_flag);
  const bool use_embree = embree_flag != "off" && embree_flag != "";
  const bool embree_timed = use_embree && absl::GetFlag(FLAGS_embree_rounds);
  if (use_embree && !quality.ok()) return quality.status();
  EmbreeOptions eo;
  if (use_embree) eo.quality = *quality;
  eo.threads = threads;

  Progress progress(absl::StrCat(scene, " ", rc->label));
  // Untimed work holds the timing lock shared, timed rounds exclusively: no
  // timed step of any process runs beside work of another (timing_lock.h).
  TimingLock lock;
  progress.Step("waiting for other processes' timed steps");
  if (absl::Status st = lock.HoldShared(); !st.ok()) return st;
  progress.Step("loading mesh");
  LoadReport load;
  LoadOptions load_options;
  load_options.max_input_bytes = absl::GetFlag(FLAGS_max_mesh_bytes);
  absl::StatusOr<TriangleSoup> soup =
      LoadMeshCached(mesh, FromWorkspace(absl::GetFlag(FLAGS_cache_dir)), &load, load_options);
  if (!soup.ok()) return soup.status();
  if (absl::Status st = CheckSceneScale(soup->Bounds()); !st.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(mesh, ": ", st.message()));
  }
  if (!load.cache_warning.empty()) std::fprintf(stderr, "kdrt: warning: %s\n", load.cache_warning.c_str());
  if (!absl::GetFlag(FLAGS_view).empty()) {
    absl::StatusOr<View> v = LoadViewFile(FromInvocationDir(absl::GetFlag(FLAGS_view)));
    if (!v.ok()) return v.status();
    view = *v;
    view_source = absl::StrCat("file:", absl::GetFlag(FLAGS_view));
  } else if (view_source.empty()) {
    view = AutoView(soup->Bounds());
    view_source = "auto";
  }

  absl::StatusOr<uint64_t> tree_budget = CheckRunMemory(
      view, rc->config.cast_shadow_rays, soup->size(), absl::GetFlag(FLAGS_memory_budget_gb));
  if (!tree_budget.ok()) return tree_budget.status();

  progress.Phase("load");
  // Everything untimed first, then the timed rounds in one stretch under the
  // lock, so that two processes' untimed work overlaps: warm-up builds, the
  // renders' warm-ups (below), then timed renders on the warm trees and last
  // the timed builds (which free the warm trees first).
  progress.Step("warm-up builds");
  TimedBuilds b;
  b.limits.max_bytes = *tree_budget;
  const auto step = [&progress](const std::string& what) { progress.Step(what); };
  absl::Status st = WarmUpBuilds(*soup, rc->config, use_embree ? &eo : nullptr, &b);
  if (!st.ok()) return st;
  progress.Phase("warm-up builds");
  const KdTree& tree = *b.tree;
  const TreeStats stats = ComputeStats(tree);
  const KdTreeTracer kd(tree);
  RenderOptions ropt;
  ropt.threads = threads;
  ropt.cast_shadow_rays = rc->config.cast_shadow_rays;
  // The renders (kdrt_lanes.h). Their warm-ups are the untimed passes every
  // run makes anyway over the frame's rays: the kd-tree's recording render
  // (the rays and hits for the counting pass, the comparison and the dump),
  // the comparison passes that trace the recorded rays through Embree (and
  // the robust Embree), and the replays' recording renders; the fast modes
  // run on the warmed tree, and each timed render must reproduce the
  // kd-tree's image and hit counts.
  LaneChoice choice;
  choice.fast = absl::GetFlag(FLAGS_fast_render);
  choice.embree_timed = embree_timed;
  choice.embree_robust = absl::GetFlag(FLAGS_embree_robust);
  choice.render = ropt;
  absl::StatusOr<LaneSet> lane_set = MakeLanes(*soup, kd, b.embree.get(), eo, choice);
  if (!lane_set.ok()) return lane_set.status();
  std::vector<Lane>& lanes = lane_set->lanes;
  const bool fast = choice.fast;
  EmbreeTracer* const robust = lane_set->robust.get();
  progress.Phase("stats", "recording rays");
  RenderOptions rec_opt = ropt;
  rec_opt.record_rays = true;
  RenderResult recorded = Render(*soup, kd, view, rec_opt);
  lanes.front().warmup_s = recorded.seconds;
  progress.Phase("recording render (kd-tree warm-up)", "counting pass");
  const std::string cost_path = FromInvocationDir(absl::GetFlag(FLAGS_cost_image));
  CostImage cost(cost_path.empty() ? 0 : view.width, cost_path.empty() ? 0 : view.height);
  const RayCounts counts = CountTraversal(tree, recorded.rays, cost_path.empty() ? nullptr : &cost);
  progress.Phase("counting pass");
  if (!cost_path.empty()) {
    if (!(st = WriteFile(cost_path, [&](const std::string& p) { return WriteCostImageNpyGz(p, cost); })).ok()) {
      return st;
    }
    progress.Phase("cost image");
  }
  Json disagreements, robust_disagreements;
  if (use_embree) {
    progress.Step("comparing with embree");
    const Disagreements d = CompareTracers(recorded.rays, *soup, kd, *b.embree);
    disagreements = d.ToJson();
    for (const std::string& ex : d.examples) std::fprintf(stderr, "kdrt: disagreement: %s\n", ex.c_str());
    progress.Phase("embree comparison (embree warm-up)");
    if (embree_timed) {
      lanes[lane_set->embree_lane].warmup_s =
          progress.phases()["embree comparison (embree warm-up)"].get<double>();
    }
    if (robust != nullptr) {
      progress.Step("comparing with embree (robust)");
      robust_disagreements = CompareTracers(recorded.rays, *soup, kd, *robust).ToJson();
      progress.Phase("embree robust comparison (its warm-up)");
      lanes[lane_set->robust_lane].warmup_s =
          progress.phases()["embree robust comparison (its warm-up)"].get<double>();
    }
  }
  if (!absl::GetFlag(FLAGS_dump_rays).empty()) {
    progress.Step("writing ray dump");
    RayDump dump{view.width, view.height, std::move(recorded.rays)};
    st = WriteRayDump(FromInvocationDir(absl::GetFlag(FLAGS_dump_rays)), dump);
    if (!st.ok()) return st;
    progress.Phase("ray dump");
  }
  recorded.rays = std::vector<RayRecord>();
  for (Lane& l : lanes) {
    if (l.tracer == &kd || l.replay != nullptr) l.last = recorded;  // to reproduce
    if (l.replay != nullptr) {  // its answers, recorded in its mode (its warm-up)
      l.replay->Record();
      l.warmup_s = Render(*soup, *l.replay, view, l.opt).seconds;
    }
  }
  recorded = RenderResult();
  const Lane& kl = lanes.front();
  progress.Step("waiting for the timing lock");
  if (!(st = lock.Acquire()).ok()) return st;
  progress.Phase("waiting for the timing lock");
  if (!(st = TimeRounds(*soup, view, repeats, budget_s, &lanes, step)).ok()) return st;
  progress.Phase("timed renders");
  lane_set->robust.reset();  // before the timed builds, as they free the other tracers
  // The lanes' tracers (the warm trees) are freed by the timed builds.
  st = TimeBuildRounds(*soup, rc->config, embree_timed ? &eo : nullptr, repeats, budget_s, step, &b);
  lock.Release();
  if (!st.ok()) return st;
  progress.Phase("timed builds");
  progress.Done();

  // Image and record.
  const RenderResult& r = kl.last;
  const double pixels = static_cast<double>(view.width) * view.height;
  const std::string png = FromInvocationDir(absl::GetFlag(FLAGS_image));
  if (!png.empty() && !(st = WriteFile(png, [&](const std::string& p) {
                          return WritePngRgb8(p, r.width, r.height, r.rgb);
                        })).ok()) {
    return st;
  }
  Json rec = {{"scene", scene}, {"mesh", mesh}, {"n_tri", soup->size()}, {"load_s", load.load_seconds},
              {"dropped_at_load",
               {{"nonfinite", load.dropped_nonfinite},
                {"degenerate", load.dropped_degenerate},
                {"point_line_faces", load.skipped_faces}}},
              {"preset", rc->preset}, {"label", rc->label},
              {"env_file", rc->env_path.empty() ? Json() : Json(rc->env_path)},
              {"overrides", rc->overrides}, {"config", ConfigJson(rc->config)},
              {"env", rc->config.ToEnvironment()}, {"view_source", view_source}, {"view", ViewToText(view)},
              {"width", view.width}, {"height", view.height}, {"lights", view.lights.size()},
              {"threads", threads}, {"repeats", repeats}, {"repeat_budget_s", budget_s}};
  rec["timing"] = {{"method", "untimed warm-ups first (a build of each tracer; renders: the kd-tree's recording render, "
                              "Embree's comparison pass), then alone under the lock rounds alternating the tracers, "
                              "renders then builds; ratios paired per round"},
                   {"rounds", kl.timed.t_r.size()}, {"lock_wait_s", lock.waited_seconds()},
                   {"phases_s", progress.phases()}};
  rec["T_B"] = Median(b.kd_runs);
  rec["T_B_runs"] = b.kd_runs;
  rec["T_B_warmup"] = b.kd_warmup;
  AddRenderTimes(kl, pixels, &rec);
  rec["rays_total"] = r.total_rays();
  AddCountsAndStats(counts, stats, r, &rec);
  rec["effects"] = EffectsJson(kl);
  rec["image"] = png.empty() ? Json() : Json(png);
  rec["image_fnv64"] = absl::StrFormat("%016x", Fnv64(r.rgb));
  AddComparisons(lanes, fast, use_embree ? &*quality : nullptr, embree_timed, b, disagreements, pixels, &rec);
  AddRobustEmbree(lanes, robust_disagreements, &rec);
  AddPassComparisons(lanes, &rec);
  Provenance prov = CollectProvenance(Workspace());
  prov.timing_lock = lock.path();
  rec["provenance"] = prov.ToJson();
  const std::string line = JsonLine(rec);
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
  const std::string record_path = FromInvocationDir(absl::GetFlag(FLAGS_record));
  if (!record_path.empty() && !(st = WriteFile(record_path, [&](const std::string& p) {
                                  return AppendLine(p, line);
                                })).ok()) {
    return st;
  }
  if (counts.result_mismatches != 0) {
    return absl::InternalError(absl::StrCat(counts.result_mismatches, " rays differ between the counting and the fast traversal"));
  }
  return absl::OkStatus();
}

}  // namespace
}  // namespace kdtree

int main(int argc, char** argv) {
  std::vector<char*> positional = absl::ParseCommandLine(argc, argv);
  if (positional.size() > 1) {
    std::fprintf(stderr, "kdrt: unexpected argument '%s'\n", positional[1]);
    return 1;
  }
  const absl::Status st = kdtree::Run();
  if (!st.ok()) {
    std::fprintf(stderr, "kdrt: %s\n", std::string(st.message()).c_str());
    return 1;
  }
  return 0;
}
