// What robustness costs in render time: the same rays traced by each preset
// with the fast (Moeller & Trumbore 1997) and the watertight (Woop, Benthin &
// Wald, JCGT 2(1), 2013) triangle test, on the same kd-tree and the same
// robust traversal (cc/kdtree/traversal.h), both reading the same leaf
// packets a vector step at a time, so the two tests are all that differ.
// The issue "Hard cases stay numerically stable" asks for this number next
// to the adversarial suite.
//
//   bazel build -c opt //cc/robust:robust_cost_bench
//   bazel-out/k8-opt/bin/cc/robust/robust_cost_bench --scene bunny --out FILE
//       [--presets default] [--repeats 5] [--width 800 --height 800]
//
// Scene: --scene NAME (data/cache/scenes/index.json, camera and light from
// data/manifest.json, as kdrt reads them), --mesh PATH (automatic view), or
// neither: a generated scene of about 100k triangles (a closed bumpy sphere of
// 81,920 triangles on a voxel terrain). Paths are relative to the working
// directory (run it from the repository root).
// Rays: the kdrt renderer's (cc/render/renderer.cc): the view's primary rays
// (closest hit), then one shadow ray per primary hit and light (any hit),
// spawned with the error-bound offset of cc/geometry/spawn.h from the
// watertight hits of the default tree, so both modes trace exactly the same
// rays. A view without a light gets the automatic view's light.
//
// Timing (issue 22, the method of kdrt and render_bench), one thread, per
// preset: the tree is built (untimed), each test traces all rays once as an
// untimed warm-up (recorded apart, never in a median), then, holding the
// machine-wide TimingLock (cc/base/timing_lock.h), --repeats rounds in each
// of which both tests trace all rays once, the order swapping every round
// (fast first in rounds 1, 3, ...). Each round gives one paired ratio,
// watertight seconds / fast seconds of that round; the record keeps every
// run and every ratio, and their medians. Every timed run must give the same
// answers as the warm-up (the traversal is deterministic).
//
// Output: one JSON line per preset (nlohmann-json), appended to --out
// (stdout when empty); the fields are listed at RecordJson below. The
// record's "provenance" (cc/base/provenance.h) names the code, the build and
// the CPU, and the timing lock its rounds held.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "cc/base/json_line.h"
#include "cc/base/median.h"
#include "cc/base/provenance.h"
#include "cc/base/timing_lock.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "cc/render/camera.h"
#include "cc/render/framing.h"
#include "cc/render/manifest.h"
#include "cc/render/secondary_rays.h"
#include "cc/render/view.h"
#include "cc/robust/preset_check.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, scene, "", "manifest scene (data/cache/scenes/index.json)");
ABSL_FLAG(std::string, mesh, "", "mesh file (default: a generated ~100k-triangle scene)");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups", "triangle-soup cache ('' = none)");
ABSL_FLAG(std::string, out, "", "JSON-lines output file (appended); stdout when empty");
ABSL_FLAG(std::string, presets, "", "comma-separated presets (default: default + the nine + the two beyond)");
ABSL_FLAG(int, width, 0, "image width (0: the view's)");
ABSL_FLAG(int, height, 0, "image height (0: the view's)");
ABSL_FLAG(int, repeats, 5, "timed rounds (each traces all rays with both tests), after one warm-up of each");
ABSL_FLAG(std::string, repo_root, "",
          "checkout whose provenance the record carries (default: $BUILD_WORKSPACE_DIRECTORY under bazel run, "
          "else the working directory)");
ABSL_FLAG(bool, list_presets, false, "print the default preset list, comma-separated, and exit");

namespace kdtree {
namespace {

using Json = nlohmann::ordered_json;

TriangleSoup GeneratedScene() {
  TriangleSoup soup = testing::BumpySphere(6, 11);  // radius about 1 at the origin
  const TriangleSoup terrain = testing::VoxelGrid(40, 4, 40, 3);
  // Terrain: 40 x 40 unit columns, scaled to 4 x 4 under the sphere.
  for (const Vec3& p : terrain.v) {
    soup.v.emplace_back(p.x * 0.1f - 2.0f, p.y * 0.1f - 1.45f, p.z * 0.1f - 2.0f);
  }
  return soup;
}

double Seconds(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The answers of one trace of all rays with one test.
struct Answers {
  std::vector<Hit> primary;
  std::vector<char> shadow;
  bool operator==(const Answers& o) const {
    if (shadow != o.shadow || primary.size() != o.primary.size()) return false;
    for (size_t i = 0; i < primary.size(); ++i) {
      const Hit &a = primary[i], &b = o.primary[i];
      if (a.tri != b.tri || std::memcmp(&a.t, &b.t, sizeof(a.t)) != 0) return false;
    }
    return true;
  }
};

// One triangle test: its warm-up, its timed runs (one per round) and answers.
struct Lane {
  Lane(IntersectionMode m, const char* n) : mode(m), name(n) {}
  IntersectionMode mode;
  const char* name;
  double warmup_s = 0;
  std::vector<double> runs;
  Answers answers;  // the warm-up's
};

double TraceOnce(const KdTree& tree, const std::vector<Ray>& primary, const std::vector<Ray>& shadow,
                 IntersectionMode mode, Answers* out) {
  out->primary.resize(primary.size());
  out->shadow.resize(shadow.size());
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < primary.size(); ++i) out->primary[i] = Intersect(tree, primary[i], WithTest(mode));
  for (size_t i = 0; i < shadow.size(); ++i) out->shadow[i] = Occluded(tree, shadow[i], WithTest(mode));
  return Seconds(start);
}

// Warm-up of each lane (untimed, outside the lock), then `repeats` rounds
// under the lock, the order swapping every round. Error: a timed run answered
// differently from its warm-up, or the lock failed.
absl::Status TimeLanes(const KdTree& tree, const std::vector<Ray>& primary, const std::vector<Ray>& shadow,
                       int repeats, TimingLock* lock, Lane* first, Lane* second) {
  for (Lane* lane : {first, second}) lane->warmup_s = TraceOnce(tree, primary, shadow, lane->mode, &lane->answers);
  if (absl::Status st = lock->Acquire(); !st.ok()) return st;
  Answers again;
  for (int r = 0; r < repeats; ++r) {
    Lane* order[2] = {first, second};
    if (r % 2 == 1) std::swap(order[0], order[1]);
    for (Lane* lane : order) {
      lane->runs.push_back(TraceOnce(tree, primary, shadow, lane->mode, &again));
      if (!(again == lane->answers)) {
        lock->Release();
        return absl::InternalError(absl::StrCat(lane->name, " test: round ", r + 1,
                                                " answered differently from its warm-up"));
      }
    }
  }
  lock->Release();
  return absl::OkStatus();
}

struct Scene {
  std::string name;
  TriangleSoup soup;
  View view;
  std::string view_source;
};

absl::StatusOr<Scene> LoadScene() {
  Scene s;
  s.name = absl::GetFlag(FLAGS_scene);
  std::string mesh = absl::GetFlag(FLAGS_mesh);
  if (!s.name.empty()) {
    absl::StatusOr<SceneRef> ref = ResolveScene(".", s.name);
    if (!ref.ok()) return ref.status();
    mesh = ref->mesh_path;
    if (ref->has_view) {
      s.view = ref->view;
      s.view_source = "manifest";
    }
  }
  if (!mesh.empty()) {
    absl::StatusOr<TriangleSoup> soup = LoadMeshCached(mesh, absl::GetFlag(FLAGS_cache_dir));
    if (!soup.ok()) return soup.status();
    s.soup = *std::move(soup);
    if (s.name.empty()) s.name = mesh.substr(mesh.find_last_of('/') + 1);
  } else {
    s.soup = GeneratedScene();
    s.name = "generated";
  }
  const View automatic = AutoView(s.soup.Bounds());
  if (s.view_source.empty()) {
    s.view = automatic;
    s.view_source = "auto";
  }
  if (s.view.lights.empty()) s.view.lights = automatic.lights;
  if (absl::GetFlag(FLAGS_width) > 0) s.view.width = absl::GetFlag(FLAGS_width);
  if (absl::GetFlag(FLAGS_height) > 0) s.view.height = absl::GetFlag(FLAGS_height);
  if (absl::Status st = s.view.Validate(s.name); !st.ok()) return st;
  return s;
}

Json LaneJson(const Lane& lane, size_t rays) {
  size_t primary_hits = 0, shadow_hits = 0;
  for (const Hit& h : lane.answers.primary) primary_hits += h.hit();
  for (char s : lane.answers.shadow) shadow_hits += s;
  const double median = Median(lane.runs);
  return {{"seconds", median},
          {"seconds_runs", lane.runs},
          {"warmup_seconds", lane.warmup_s},
          {"rays_per_s", median > 0 ? Json(rays / median) : Json()},
          {"primary_hits", primary_hits},
          {"shadow_hits", shadow_hits}};
}

std::string RepoRoot() {
  if (!absl::GetFlag(FLAGS_repo_root).empty()) return absl::GetFlag(FLAGS_repo_root);
  const char* ws = std::getenv("BUILD_WORKSPACE_DIRECTORY");
  return ws != nullptr && *ws != '\0' ? ws : ".";
}

std::string Percent(double ratio) { return absl::StrFormat("%+.1f%%", 100.0 * (ratio - 1.0)); }

int Run() {
  std::vector<std::string> presets = robust::CheckedPresets();
  if (!absl::GetFlag(FLAGS_presets).empty()) {
    presets = absl::StrSplit(absl::GetFlag(FLAGS_presets), ',', absl::SkipEmpty());
  }
  if (absl::GetFlag(FLAGS_list_presets)) {
    std::printf("%s\n", absl::StrJoin(presets, ",").c_str());
    return 0;
  }
  absl::StatusOr<Scene> scene = LoadScene();
  if (!scene.ok()) {
    std::fprintf(stderr, "robust_cost_bench: %s\n", scene.status().ToString().c_str());
    return 1;
  }
  const TriangleSoup& soup = scene->soup;
  const int repeats = std::max(1, absl::GetFlag(FLAGS_repeats));
  // The renderer's rays: primary, then shadow rays from the default tree's
  // watertight hits.
  const Camera camera(scene->view.camera, scene->view.width, scene->view.height);
  std::vector<Ray> primary, shadow;
  {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
    if (!tree.ok()) {
      std::fprintf(stderr, "robust_cost_bench: %s\n", tree.status().ToString().c_str());
      return 1;
    }
    for (int y = 0; y < camera.height(); ++y) {
      for (int x = 0; x < camera.width(); ++x) primary.push_back(camera.PrimaryRay(x, y));
    }
    for (const Ray& ray : primary) {
      const Hit h = Intersect(*tree, ray);
      if (!h.hit()) continue;
      const SurfacePoint sp = MakeSurfacePoint(soup, ray, h);
      for (const PointLight& light : scene->view.lights) {
        shadow.push_back(ShadowRay(sp, light.position));
      }
    }
  }
  std::FILE* out = stdout;
  if (!absl::GetFlag(FLAGS_out).empty()) {
    out = std::fopen(absl::GetFlag(FLAGS_out).c_str(), "a");
    if (out == nullptr) {
      std::fprintf(stderr, "robust_cost_bench: cannot open %s\n", absl::GetFlag(FLAGS_out).c_str());
      return 1;
    }
  }
  // The progress table: on stdout, unless the records go there.
  std::FILE* table = out == stdout ? stderr : stdout;
  std::fprintf(table,
               "%s: %zu triangles, %dx%d (%s view), %zu primary + %zu shadow rays, a warm-up and %d rounds "
               "per test, single thread\n",
               scene->name.c_str(), soup.size(), scene->view.width, scene->view.height,
               scene->view_source.c_str(), primary.size(), shadow.size(), repeats);
  std::fprintf(table, "%-18s %9s %9s %11s %11s %27s %8s\n", "preset", "fast s", "robust s", "fast Mray/s",
               "robust Mray/s", "cost: paired median [range]", "mismatch");
  // The provenance's code identity runs cc/base/source_id.sh once, here.
  Provenance prov = CollectProvenance(RepoRoot());
  TimingLock lock;
  // Untimed work holds the lock shared, timed rounds exclusively (timing_lock.h).
  if (const absl::Status st = lock.HoldShared(); !st.ok()) {
    std::fprintf(stderr, "%s\n", std::string(st.message()).c_str());
    return 1;
  }
  prov.timing_lock = lock.path();
  const Json provenance = prov.ToJson();
  const size_t rays = primary.size() + shadow.size();
  for (const std::string& name : presets) {
    absl::StatusOr<Config> config = robust::ConfigFor(name);
    absl::StatusOr<KdTree> tree =
        config.ok() ? BuildKdTree(soup, *config) : absl::StatusOr<KdTree>(config.status());
    if (!tree.ok()) {
      std::fprintf(stderr, "robust_cost_bench: %s: %s\n", name.c_str(), tree.status().ToString().c_str());
      return 1;
    }
    Lane fast(IntersectionMode::kFast, "fast");
    Lane robust(IntersectionMode::kWatertight, "watertight");
    const double waited_before = lock.waited_seconds();
    if (absl::Status st = TimeLanes(*tree, primary, shadow, repeats, &lock, &fast, &robust); !st.ok()) {
      std::fprintf(stderr, "robust_cost_bench: %s: %s\n", name.c_str(), st.ToString().c_str());
      return 1;
    }
    size_t mismatches = 0, other_t = 0;
    for (size_t i = 0; i < primary.size(); ++i) {
      const Hit &f = fast.answers.primary[i], &w = robust.answers.primary[i];
      mismatches += f.tri != w.tri;  // hit versus miss, or another triangle
      other_t += f.tri == w.tri && f.hit() && f.t != w.t;
    }
    for (size_t i = 0; i < shadow.size(); ++i) mismatches += fast.answers.shadow[i] != robust.answers.shadow[i];
    const std::vector<double> ratios = PairedRatios(robust.runs, fast.runs);
    const double ratio = Median(ratios);
    const double lo = *std::min_element(ratios.begin(), ratios.end());
    const double hi = *std::max_element(ratios.begin(), ratios.end());
    // The record. Times in seconds; "paired_ratio*" are watertight / fast.
    Json rec = {{"scene", scene->name},
                {"triangles", soup.size()},
                {"view", scene->view_source},
                {"width", scene->view.width},
                {"height", scene->view.height},
                {"preset", name},
                {"threads", 1},
                {"rays", rays},
                {"primary_rays", primary.size()},
                {"shadow_rays", shadow.size()},
                {"build_seconds", tree->build_seconds},
                {"repeats", repeats},
                {"timing",
                 {{"method",
                   "warm-up of each test excluded and recorded apart, then rounds alternating the tests "
                   "under the timing lock; ratios paired per round"},
                  {"order", "fast first in odd rounds, watertight first in even rounds"},
                  {"rounds", ratios.size()},
                  {"lock_wait_s", lock.waited_seconds() - waited_before}}},
                {"fast", LaneJson(fast, rays)},
                {"watertight", LaneJson(robust, rays)},
                {"paired_ratio_runs", ratios},
                {"paired_ratio", ratio},
                {"paired_ratio_min", lo},
                {"paired_ratio_max", hi},
                {"mismatches_between_modes", mismatches},
                {"same_triangle_other_t", other_t},
                {"provenance", provenance}};
    const std::string line = JsonLine(rec) + "\n";
    if (std::fputs(line.c_str(), out) < 0 || std::fflush(out) != 0) {
      std::fprintf(stderr, "robust_cost_bench: cannot write %s\n", absl::GetFlag(FLAGS_out).c_str());
      return 1;
    }
    const double fm = Median(fast.runs), rm = Median(robust.runs);
    const std::string cost = absl::StrCat(Percent(ratio), " [", Percent(lo), ", ", Percent(hi), "]",
                                          lo <= 1.0 && 1.0 <= hi ? " noise" : "");
    std::fprintf(table, "%-18s %9.3f %9.3f %11.3f %11.3f %27s %8zu\n", name.c_str(), fm, rm, rays / fm * 1e-6,
                 rays / rm * 1e-6, cost.c_str(), mismatches);
    std::fflush(table);
  }
  if (out != stdout) std::fclose(out);
  return 0;
}

}  // namespace
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return kdtree::Run();
}
