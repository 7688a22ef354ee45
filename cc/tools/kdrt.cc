// kdrt: builds the kd-tree for one scene and configuration, renders it, and
// records the report's measurements (tables 1-10) as one JSON line.
//
//   bazel build --config=opt //cc/tools:kdrt
//   bazel-bin/cc/tools/kdrt --mesh=/tmp/gl/usr/share/glmark2/models/bunny.obj
//       --preset=clipping-pruning --out=/tmp/kdrt --repeats=3 --embree=medium
//
// Steps: load the mesh (through the soup cache); build the tree `repeats`
// times (T_B = median; --repeat_budget_s caps the runs of a slow step, at
// least one); render `repeats` times on the non-counting fast path
// (T_R = median; renderer.h); render once more recording every ray (the same
// rays: the renderer is deterministic) and replay them with the counting
// traversal for N_IT / N_TR (traversal_counts.h); optionally dump the rays;
// optionally (--fast_render) time the renderer's packets with origin skipping
// too (record field fast_render: its T_R, runs, primary and shadow seconds);
// optionally build and render with
// Embree the same way and trace the recorded
// rays with it to count disagreements (compare.h). Writes
// <out>/<scene>_<label>.png and appends the record to <out>/results.jsonl;
// the record is also printed on stdout. Exit code 1 on any error.
//
// perf_krays = 640,000 / T_R / 1000 in the report's sense: primary rays per
// second of render time although T_R includes the shadow rays
// (width * height in place of 640,000); all_rays_per_s counts every ray.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
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
#include "cc/embree/embree_tracer.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/stats.h"
#include "cc/render/compare.h"
#include "cc/render/json.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/manifest.h"
#include "cc/render/png.h"
#include "cc/render/ray_dump.h"
#include "cc/render/renderer.h"
#include "cc/render/traversal_counts.h"
#include "cc/render/view.h"
#include "cc/tools/kdrt_config.h"
#include "cc/tools/paths.h"
#include "cc/tools/run_info.h"
#include "cc/tools/timed_render.h"

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
ABSL_FLAG(std::string, out, "", "Output directory: <scene>_<label>.png and results.jsonl ('' = no files).");
ABSL_FLAG(int, threads, 1, "Render threads (1 = no TBB); also Embree's device threads.");
ABSL_FLAG(int, repeats, 5, "Builds and renders per tracer; medians are reported.");
ABSL_FLAG(double, repeat_budget_s, 0,
          "Stop repeating a timed build or render once its runs took this many seconds in all "
          "(at least one run; 0 = always --repeats runs). Every run is recorded.");
ABSL_FLAG(std::string, dump_rays, "", "Write every ray and its kd-tree result here (cc/render/ray_dump.h).");
ABSL_FLAG(std::string, embree, "off", "off | low | medium | high: also build and render with Embree.");
ABSL_FLAG(bool, fast_render, false,
          "Also time the renderer's fastest mode (primary and shadow rays in packets of 2x2 "
          "pixels, shadow rays leaving their origin triangle untested): record field "
          "fast_render, held to the timed image.");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups", "Triangle-soup cache directory ('' = none).");

namespace kdtree {
namespace {

std::string Workspace() {
  const char* ws = std::getenv("BUILD_WORKSPACE_DIRECTORY");
  return ws != nullptr && *ws != '\0' ? ws : ".";
}
std::string FromWorkspace(const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  return absl::StrCat(Workspace(), "/", path);
}
std::string MeshStem(const std::string& path) {
  std::string base = path.substr(path.find_last_of('/') + 1);
  if (base.size() > 3 && base.substr(base.size() - 3) == ".gz") base.resize(base.size() - 3);
  const size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

// "\r<message>" on a terminal, nothing otherwise.
class Progress {
 public:
  explicit Progress(std::string prefix) : prefix_(std::move(prefix)), tty_(isatty(STDERR_FILENO)) {}
  ~Progress() { Done(); }
  void Step(const std::string& what) {
    if (!tty_) return;
    std::fprintf(stderr, "\r\033[Kkdrt %s: %s", prefix_.c_str(), what.c_str());
    std::fflush(stderr);
    shown_ = true;
  }
  void Done() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
    shown_ = false;
  }

 private:
  std::string prefix_;
  bool tty_, shown_ = false;
};

uint64_t Fnv64(const std::vector<uint8_t>& bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
  return h;
}

std::string TraversalJson(const TraversalCounters& c) {
  const double n = c.rays ? static_cast<double>(c.rays) : 1.0;
  return absl::StrFormat("{\"rays\": %d, \"N_IT\": %s, \"N_TR\": %s, \"leaves\": %s}", c.rays,
                         JsonNumber(c.triangle_tests / n), JsonNumber(c.inner_visits / n),
                         JsonNumber(c.leaf_visits / n));
}

// mkdir -p.
absl::Status MakeDirs(const std::string& dir) {
  for (size_t i = 1; i <= dir.size(); ++i) {
    if (i < dir.size() && dir[i] != '/') continue;
    const std::string part = dir.substr(0, i);
    if (mkdir(part.c_str(), 0755) != 0 && errno != EEXIST) {
      return absl::InternalError(absl::StrCat(part, ": cannot create directory: ", std::strerror(errno)));
    }
  }
  return absl::OkStatus();
}

absl::Status Run() {
  const int repeats = absl::GetFlag(FLAGS_repeats), threads = absl::GetFlag(FLAGS_threads);
  if (repeats < 1 || threads < 1) return absl::InvalidArgumentError("--repeats and --threads must be >= 1");
  const double budget_s = absl::GetFlag(FLAGS_repeat_budget_s);
  // Scene and mesh.
  std::string scene = absl::GetFlag(FLAGS_scene), mesh = FromInvocationDir(absl::GetFlag(FLAGS_mesh));
  View view;
  std::string view_source;
  if (!scene.empty() && mesh.empty()) {
    absl::StatusOr<SceneRef> ref = ResolveScene(Workspace(), scene);
    if (!ref.ok()) return ref.status();
    mesh = ref->mesh_path;
    if (ref->has_view) {
      view = ref->view;
      view_source = "manifest";
    }
  } else if (!scene.empty()) {
    absl::StatusOr<bool> has = LoadManifestView(Workspace(), scene, &view);
    if (!has.ok()) return has.status();
    if (*has) view_source = "manifest";
  } else if (!mesh.empty()) {
    scene = MeshStem(mesh);
  } else {
    return absl::InvalidArgumentError("give --scene or --mesh");
  }
  // Configuration.
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
  absl::StatusOr<ResolvedConfig> rc = ResolveConfig(cf);
  if (!rc.ok()) return rc.status();
  const std::string embree_flag = absl::GetFlag(FLAGS_embree);
  absl::StatusOr<EmbreeQuality> quality = ParseEmbreeQuality(embree_flag);
  const bool use_embree = embree_flag != "off" && embree_flag != "";
  if (use_embree && !quality.ok()) return quality.status();

  Progress progress(absl::StrCat(scene, " ", rc->label));
  progress.Step("loading mesh");
  LoadReport load;
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(mesh, FromWorkspace(absl::GetFlag(FLAGS_cache_dir)), &load);
  if (!soup.ok()) return soup.status();
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

  // kd-tree: builds, timed renders, recorded render, counting pass.
  std::vector<double> tb_runs;
  absl::StatusOr<KdTree> tree;
  for (int i = 0; MoreRuns(tb_runs, repeats, budget_s); ++i) {
    progress.Step(absl::StrFormat("build %d/%d", i + 1, repeats));
    tree = BuildKdTree(*soup, rc->config);
    if (!tree.ok()) return tree.status();
    tb_runs.push_back(tree->build_seconds);
  }
  const TreeStats stats = ComputeStats(*tree);
  const KdTreeTracer kd(*tree);
  RenderOptions ropt;
  ropt.threads = threads;
  ropt.cast_shadow_rays = rc->config.cast_shadow_rays;
  const auto step = [&progress](const std::string& what) { progress.Step(what); };
  const Timed kt = TimeRenders(*soup, kd, view, ropt, repeats, budget_s, step);
  // Beyond the report: the same frame with packets and origin skipping
  // (RenderOptions::packets, skip_origin); results, hence the image, must be
  // the timed ones.
  std::string fast_json = "null";
  if (absl::GetFlag(FLAGS_fast_render)) {
    RenderOptions fo = ropt;
    fo.packets = true;
    fo.skip_origin = true;
    const Timed ft = TimeRenders(*soup, kd, view, fo, repeats, budget_s, step);
    if (ft.last.rgb != kt.last.rgb || ft.last.s_hit != kt.last.s_hit ||
        ft.last.p_hit != kt.last.p_hit) {
      return absl::InternalError("the fast render (packets, origin untested) differs from the timed one");
    }
    fast_json = absl::StrFormat("{\"T_R\": %s, \"T_R_runs\": %s, \"primary_s\": %s, \"shadow_s\": %s}",
                                JsonNumber(Median(ft.t_r)), JsonNumberArray(ft.t_r),
                                JsonNumber(Median(ft.t_primary)), JsonNumber(Median(ft.t_shadow)));
  }
  progress.Step("recording rays");
  RenderOptions rec_opt = ropt;
  rec_opt.record_rays = true;
  RenderResult recorded = Render(*soup, kd, view, rec_opt);
  if (recorded.rgb != kt.last.rgb || recorded.s_hit != kt.last.s_hit) {
    return absl::InternalError("the recording render differs from the timed one (non-deterministic?)");
  }
  progress.Step("counting pass");
  const RayCounts counts = CountTraversal(*tree, recorded.rays);
  if (!absl::GetFlag(FLAGS_dump_rays).empty()) {
    progress.Step("writing ray dump");
    RayDump dump{view.width, view.height, std::move(recorded.rays)};
    absl::Status st = WriteRayDump(FromInvocationDir(absl::GetFlag(FLAGS_dump_rays)), dump);
    if (!st.ok()) return st;
    recorded.rays = std::move(dump.records);
  }

  const double pixels = static_cast<double>(view.width) * view.height;
  const double t_r = Median(kt.t_r);
  const RenderResult& r = kt.last;
  std::string embree_json = "null", disagree_json = "null", ratio_json = "null";
  if (use_embree) {
    EmbreeOptions eo;
    eo.quality = *quality;
    eo.threads = threads;
    std::vector<double> eb_runs;
    std::unique_ptr<EmbreeTracer> embree;
    for (int i = 0; MoreRuns(eb_runs, repeats, budget_s); ++i) {
      progress.Step(absl::StrFormat("embree build %d/%d", i + 1, repeats));
      embree.reset();
      absl::StatusOr<std::unique_ptr<EmbreeTracer>> e = EmbreeTracer::Create(*soup, eo);
      if (!e.ok()) return e.status();
      embree = *std::move(e);
      eb_runs.push_back(embree->build_seconds());
    }
    const Timed et = TimeRenders(*soup, *embree, view, ropt, repeats, budget_s, step);
    const double e_tr = Median(et.t_r);
    const RenderResult& er = et.last;
    progress.Step("comparing with embree");
    const Disagreements d = CompareTracers(recorded.rays, *soup, kd, *embree);
    disagree_json = d.ToJson();
    for (const std::string& ex : d.examples) std::fprintf(stderr, "kdrt: disagreement: %s\n", ex.c_str());
    ratio_json = JsonNumber(e_tr / t_r);
    embree_json = absl::StrFormat(
        "{\"quality\": %s, \"T_B\": %s, \"T_B_runs\": %s, \"T_R\": %s, \"T_R_runs\": %s, "
        "\"perf_krays\": %s, \"all_rays_per_s\": %s, \"P_hit\": %d, \"P_miss\": %d, \"S_hit\": %d, "
        "\"S_miss\": %d, \"effects\": {%s, %s, %s}, \"disagreements\": %d, "
        "\"disagreements_grazing\": %d, \"disagreements_at_origin\": %d, \"disagreements_t_guard\": %d, "
        "\"disagreements_other\": %d, "
        "\"perf_ratio_kd_over_embree\": %s}",
        JsonQuote(EmbreeQualityName(*quality)), JsonNumber(Median(eb_runs)), JsonNumberArray(eb_runs),
        JsonNumber(e_tr), JsonNumberArray(et.t_r), JsonNumber(pixels / e_tr / 1000.0),
        JsonNumber(er.total_rays() / e_tr), er.p_hit, er.p_miss, er.s_hit, er.s_miss,
        EffectJson("primary", er.primary.rays, et.t_primary), EffectJson("shadow", er.shadow.rays, et.t_shadow),
        EffectJson("ao", er.ao.rays, et.t_ao), d.all.total(), d.all.grazing, d.all.at_origin, d.all.t_guard, d.all.other(),
        ratio_json);
  }
  progress.Done();

  // Image and record.
  const std::string out = FromInvocationDir(absl::GetFlag(FLAGS_out));
  std::string png = "";
  if (!out.empty()) {
    absl::Status st = MakeDirs(out);
    if (!st.ok()) return st;
    png = absl::StrCat(out, "/", scene, "_", rc->label, ".png");
    st = WritePngRgb8(png, r.width, r.height, r.rgb);
    if (!st.ok()) return st;
  }
  const Config& c = rc->config;
  std::string tree_json = StatsToJson(stats);
  tree_json = tree_json.substr(1, tree_json.size() - 2);  // members only
  const std::string record = absl::StrFormat(
      "{\"scene\": %s, \"mesh\": %s, \"n_tri\": %d, \"load_s\": %s, \"preset\": %s, \"label\": %s, "
      "\"env_file\": %s, \"overrides\": [%s], \"config\": {\"max_depth\": %d, \"max_leaf_size\": %d, "
      "\"use_binning\": %s, \"use_driving_axis\": %s, \"bins\": %d, \"use_clipping\": %s, "
      "\"use_pruning\": %s, \"cast_shadow_rays\": %s, \"seed_compatible\": %s}, \"env\": %s, "
      "\"view_source\": %s, \"view\": %s, \"width\": %d, \"height\": %d, \"lights\": %d, "
      "\"threads\": %d, \"repeats\": %d, \"repeat_budget_s\": %s, \"T_B\": %s, \"T_B_runs\": %s, \"T_R\": %s, \"T_R_runs\": %s, "
      "\"perf_krays\": %s, \"all_rays_per_s\": %s, \"rays_total\": %d, \"N_IT\": %s, \"N_TR\": %s, "
      "\"traversal\": {\"primary\": %s, \"shadow\": %s, \"ao\": %s}, \"counting_mismatches\": %d, %s, "
      "\"P_hit\": %d, \"P_miss\": %d, \"S_hit\": %d, \"S_miss\": %d, \"AO_hit\": %d, \"AO_miss\": %d, "
      "\"effects\": {%s, %s, %s}, \"image\": %s, \"image_fnv64\": \"%016x\", \"embree\": %s, "
      "\"disagreements\": %s, \"perf_ratio_kd_over_embree\": %s, \"fast_render\": %s, %s}",
      JsonQuote(scene), JsonQuote(mesh), soup->size(), JsonNumber(load.load_seconds),
      JsonQuote(rc->preset), JsonQuote(rc->label),
      rc->env_path.empty() ? "null" : JsonQuote(rc->env_path),
      rc->overrides.empty() ? "" : absl::StrCat("\"", absl::StrJoin(rc->overrides, "\", \""), "\""),
      c.max_depth, c.max_leaf_size, c.use_binning ? "true" : "false",
      c.use_driving_axis ? "true" : "false", c.bins, c.use_clipping ? "true" : "false",
      c.use_pruning ? "true" : "false", c.cast_shadow_rays ? "true" : "false",
      c.seed_compatible ? "true" : "false", JsonQuote(c.ToEnvironment()), JsonQuote(view_source),
      JsonQuote(ViewToText(view)), view.width, view.height, view.lights.size(), threads, repeats, JsonNumber(budget_s),
      JsonNumber(Median(tb_runs)), JsonNumberArray(tb_runs), JsonNumber(t_r), JsonNumberArray(kt.t_r),
      JsonNumber(pixels / t_r / 1000.0), JsonNumber(r.total_rays() / t_r), r.total_rays(),
      JsonNumber(counts.n_it()), JsonNumber(counts.n_tr()), TraversalJson(counts.by_kind[0]),
      TraversalJson(counts.by_kind[1]), TraversalJson(counts.by_kind[2]), counts.result_mismatches,
      tree_json, r.p_hit, r.p_miss, r.s_hit, r.s_miss, r.ao_hit, r.ao_miss,
      EffectJson("primary", r.primary.rays, kt.t_primary), EffectJson("shadow", r.shadow.rays, kt.t_shadow),
      EffectJson("ao", r.ao.rays, kt.t_ao), png.empty() ? "null" : JsonQuote(png), Fnv64(r.rgb),
      embree_json, disagree_json, ratio_json, fast_json, CollectRunInfo(Workspace()).ToJson());
  std::printf("%s\n", record.c_str());
  std::fflush(stdout);
  if (!out.empty()) {
    const std::string path = absl::StrCat(out, "/results.jsonl");
    FILE* f = std::fopen(path.c_str(), "a");
    if (f == nullptr || std::fprintf(f, "%s\n", record.c_str()) < 0 || std::fclose(f) != 0) {
      return absl::InternalError(absl::StrCat(path, ": cannot append"));
    }
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
