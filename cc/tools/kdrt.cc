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
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cc/base/json_line.h"
#include "cc/base/median.h"
#include "cc/base/provenance.h"
#include "cc/base/quiet_cpu.h"
#include "cc/base/timing_lock.h"
#include "cc/embree/embree_tracer.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/stats.h"
#include "cc/render/framing.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/manifest.h"
#include "cc/render/png.h"
#include "cc/render/renderer.h"
#include "cc/render/view.h"
#include "cc/tools/kdrt_config.h"
#include "cc/tools/kdrt_lanes.h"
#include "cc/tools/kdrt_limits.h"
#include "cc/tools/kdrt_passes.h"
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
ABSL_FLAG(bool, triangle_bvh, false,
          "With --fast_render: also time the fastest mode's rays, one at a time and in its "
          "packets, through a BVH of whole triangles traced by the same kernels (a baseline, "
          "not a kd-tree: cc/kdtree/triangle_bvh.h); record field fast_render.triangle_bvh, "
          "held to the timed image.");
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

// The run's flags, checked, with the scene, its view (manifest or none yet)
// and the configuration resolved.
struct RunFlags {
  int repeats = 0, threads = 0;
  double budget_s = 0;
  std::string scene, mesh, view_source;
  View view;
  ResolvedConfig rc;
  bool use_embree = false, embree_timed = false;
  EmbreeQuality quality = EmbreeQuality::kMedium;
  EmbreeOptions eo;
};

absl::StatusOr<RunFlags> ReadRunFlags() {
  RunFlags f;
  f.repeats = absl::GetFlag(FLAGS_repeats);
  f.threads = absl::GetFlag(FLAGS_threads);
  if (f.repeats < 1 || f.threads < 1) return absl::InvalidArgumentError("--repeats and --threads must be >= 1");
  f.budget_s = absl::GetFlag(FLAGS_repeat_budget_s);
  f.scene = absl::GetFlag(FLAGS_scene);
  f.mesh = FromInvocationDir(absl::GetFlag(FLAGS_mesh));
  if (absl::Status st = ResolveSceneFlags(&f.scene, &f.mesh, &f.view, &f.view_source); !st.ok()) return st;
  absl::StatusOr<ResolvedConfig> rc = ResolveConfig(ConfigFlagsFromCommandLine());
  if (!rc.ok()) return rc.status();
  f.rc = *std::move(rc);
  const std::string embree_flag = absl::GetFlag(FLAGS_embree);
  f.use_embree = embree_flag != "off" && embree_flag != "";
  f.embree_timed = f.use_embree && absl::GetFlag(FLAGS_embree_rounds);
  if (f.use_embree) {
    absl::StatusOr<EmbreeQuality> quality = ParseEmbreeQuality(embree_flag);
    if (!quality.ok()) return quality.status();
    f.quality = *quality;
    f.eo.quality = *quality;
  }
  f.eo.threads = f.threads;
  return f;
}

// The mesh (through the soup cache), checked; the view from --view, else the
// manifest's, else AutoView's.
absl::StatusOr<TriangleSoup> LoadScene(RunFlags* f, LoadReport* load) {
  LoadOptions load_options;
  load_options.max_input_bytes = absl::GetFlag(FLAGS_max_mesh_bytes);
  absl::StatusOr<TriangleSoup> soup =
      LoadMeshCached(f->mesh, FromWorkspace(absl::GetFlag(FLAGS_cache_dir)), load, load_options);
  if (!soup.ok()) return soup.status();
  if (absl::Status st = CheckSceneScale(soup->Bounds()); !st.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(f->mesh, ": ", st.message()));
  }
  if (!load->cache_warning.empty()) std::fprintf(stderr, "kdrt: warning: %s\n", load->cache_warning.c_str());
  if (!absl::GetFlag(FLAGS_view).empty()) {
    absl::StatusOr<View> v = LoadViewFile(FromInvocationDir(absl::GetFlag(FLAGS_view)));
    if (!v.ok()) return v.status();
    f->view = *v;
    f->view_source = absl::StrCat("file:", absl::GetFlag(FLAGS_view));
  } else if (f->view_source.empty()) {
    f->view = AutoView(soup->Bounds());
    f->view_source = "auto";
  }
  return soup;
}

// The record's fields that describe the run: scene, mesh, configuration,
// view and the timing method.
Json RunFields(const RunFlags& f, const TriangleSoup& soup, const LoadReport& load, size_t rounds,
               const TimingLock& lock, const Progress& progress, const Json& cpu) {
  const ResolvedConfig& rc = f.rc;
  Json rec = {{"scene", f.scene}, {"mesh", f.mesh}, {"n_tri", soup.size()}, {"load_s", load.load_seconds},
              {"dropped_at_load",
               {{"nonfinite", load.dropped_nonfinite},
                {"degenerate", load.dropped_degenerate},
                {"point_line_faces", load.skipped_faces}}},
              {"preset", rc.preset}, {"label", rc.label},
              {"env_file", rc.env_path.empty() ? Json() : Json(rc.env_path)},
              {"overrides", rc.overrides}, {"config", ConfigJson(rc.config)},
              {"env", rc.config.ToEnvironment()}, {"view_source", f.view_source}, {"view", ViewToText(f.view)},
              {"width", f.view.width}, {"height", f.view.height}, {"lights", f.view.lights.size()},
              {"threads", f.threads}, {"repeats", f.repeats}, {"repeat_budget_s", f.budget_s}};
  rec["timing"] = {{"method", "untimed warm-ups first (a build of each tracer; renders: the kd-tree's recording render, "
                              "Embree's comparison pass), then alone under the lock rounds alternating the tracers, "
                              "renders (one thread: on the quieter CPU) then builds; ratios paired per round"},
                   {"rounds", rounds}, {"lock_wait_s", lock.waited_seconds()},
                   {"phases_s", progress.phases()}, {"cpu", cpu["cpu"]},
                   {"cpu_probe_ms", cpu["cpu_probe_ms"]}};
  return rec;
}

absl::Status Run() {
  absl::StatusOr<RunFlags> flags = ReadRunFlags();
  if (!flags.ok()) return flags.status();
  RunFlags& f = *flags;
  const ResolvedConfig& rc = f.rc;

  Progress progress(absl::StrCat(f.scene, " ", rc.label));
  // Untimed work holds the timing lock shared, timed rounds exclusively: no
  // timed step of any process runs beside work of another (timing_lock.h).
  TimingLock lock;
  progress.Step("waiting for other processes' timed steps");
  if (absl::Status st = lock.HoldShared(); !st.ok()) return st;
  progress.Step("loading mesh");
  LoadReport load;
  absl::StatusOr<TriangleSoup> soup = LoadScene(&f, &load);
  if (!soup.ok()) return soup.status();
  absl::StatusOr<uint64_t> tree_budget = CheckRunMemory(
      f.view, rc.config.cast_shadow_rays, soup->size(), absl::GetFlag(FLAGS_memory_budget_gb));
  if (!tree_budget.ok()) return tree_budget.status();

  progress.Phase("load");
  // Everything untimed first, then the timed rounds in one stretch under the
  // lock, so that two processes' untimed work overlaps: warm-up builds, the
  // renders' warm-ups (UntimedPasses), then timed renders on the warm trees
  // and last the timed builds (which free the warm trees first).
  progress.Step("warm-up builds");
  TimedBuilds b;
  b.limits.max_bytes = *tree_budget;
  const auto step = [&progress](const std::string& what) { progress.Step(what); };
  absl::Status st = WarmUpBuilds(*soup, rc.config, f.use_embree ? &f.eo : nullptr, &b);
  if (!st.ok()) return st;
  progress.Phase("warm-up builds");
  const KdTree& tree = *b.tree;
  const TreeStats stats = ComputeStats(tree);
  const KdTreeTracer kd(tree);
  RenderOptions ropt;
  ropt.threads = f.threads;
  ropt.cast_shadow_rays = rc.config.cast_shadow_rays;
  // The renders (kdrt_lanes.h); the fast modes run on the warmed tree, and
  // each timed render must reproduce the kd-tree's image and hit counts.
  LaneChoice choice;
  choice.fast = absl::GetFlag(FLAGS_fast_render);
  choice.embree_timed = f.embree_timed;
  choice.embree_robust = absl::GetFlag(FLAGS_embree_robust);
  choice.triangle_bvh = absl::GetFlag(FLAGS_triangle_bvh);
  choice.render = ropt;
  choice.bvh_budget = *tree_budget > TreeBytes(tree) ? *tree_budget - TreeBytes(tree) : 0;
  absl::StatusOr<LaneSet> lane_set = MakeLanes(*soup, tree, kd, b.embree.get(), f.eo, choice);
  if (!lane_set.ok()) return lane_set.status();
  std::vector<Lane>& lanes = lane_set->lanes;
  PassOutputs outputs;
  outputs.cost_image = FromInvocationDir(absl::GetFlag(FLAGS_cost_image));
  outputs.dump_rays = FromInvocationDir(absl::GetFlag(FLAGS_dump_rays));
  absl::StatusOr<UntimedResults> untimed =
      UntimedPasses(*soup, tree, kd, f.use_embree ? b.embree.get() : nullptr, f.embree_timed, f.view,
                    ropt, outputs, &*lane_set, &progress);
  if (!untimed.ok()) return untimed.status();
  const Lane& kl = lanes.front();
  progress.Step("waiting for the timing lock");
  if (!(st = lock.Acquire()).ok()) return st;
  progress.Phase("waiting for the timing lock");
  // One render thread: the timed renders on the quieter CPU (quiet_cpu.h);
  // the timed builds may use every CPU.
  std::optional<ScopedQuietCpu> quiet;
  if (f.threads == 1) quiet.emplace();
  if (!(st = TimeRounds(*soup, f.view, f.repeats, f.budget_s, &lanes, step)).ok()) return st;
  const Json cpu = QuietCpuJson(quiet ? &*quiet : nullptr);
  quiet.reset();
  progress.Phase("timed renders");
  // Before the timed builds, as they free the other tracers (the BVH's
  // build time is kept: the record's fast_render.single_bvh.build_s).
  lane_set->robust.reset();
  lane_set->bvh.reset();
  lane_set->triangle_bvh.reset();
  // The lanes' tracers (the warm trees) are freed by the timed builds.
  st = TimeBuildRounds(*soup, rc.config, f.embree_timed ? &f.eo : nullptr, f.repeats, f.budget_s, step, &b);
  lock.Release();
  if (!st.ok()) return st;
  progress.Phase("timed builds");
  progress.Done();

  // Image and record.
  const RenderResult& r = kl.last;
  const double pixels = static_cast<double>(f.view.width) * f.view.height;
  const std::string png = FromInvocationDir(absl::GetFlag(FLAGS_image));
  if (!png.empty() && !(st = WriteCreatingDirectory(png, [&](const std::string& p) {
                          return WritePngRgb8(p, r.width, r.height, r.rgb);
                        })).ok()) {
    return st;
  }
  Json rec = RunFields(f, *soup, load, kl.timed.t_r.size(), lock, progress, cpu);
  rec["T_B"] = Median(b.kd_runs);
  rec["T_B_runs"] = b.kd_runs;
  rec["T_B_warmup"] = b.kd_warmup;
  AddRenderTimes(kl, pixels, &rec);
  rec["rays_total"] = r.total_rays();
  AddCountsAndStats(untimed->counts, stats, r, &rec);
  rec["effects"] = EffectsJson(kl);
  rec["image"] = png.empty() ? Json() : Json(png);
  rec["image_fnv64"] = absl::StrFormat("%016x", Fnv64(r.rgb));
  AddComparisons(lanes, choice.fast, f.use_embree ? &f.quality : nullptr, f.embree_timed, b,
                 untimed->disagreements, pixels, lane_set->bvh_built, &rec);
  AddRobustEmbree(lanes, untimed->robust_disagreements, &rec);
  AddTriangleBvh(lanes, lane_set->triangle_bvh_build_s, lane_set->triangle_bvh_bytes, &rec);
  AddPassComparisons(lanes, &rec);
  Provenance prov = CollectProvenance(Workspace());
  prov.timing_lock = lock.path();
  rec["provenance"] = prov.ToJson();
  const std::string line = JsonLine(rec);
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
  const std::string record_path = FromInvocationDir(absl::GetFlag(FLAGS_record));
  if (!record_path.empty() && !(st = WriteCreatingDirectory(record_path, [&](const std::string& p) {
                                  return AppendLine(p, line);
                                })).ok()) {
    return st;
  }
  if (untimed->counts.result_mismatches != 0) {
    return absl::InternalError(absl::StrCat(untimed->counts.result_mismatches,
                                            " rays differ between the counting and the fast traversal"));
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
