// What robustness costs in render time: the same rays traced by each preset
// with the fast (Moeller & Trumbore 1997) and the watertight (Woop, Benthin &
// Wald, JCGT 2(1), 2013) triangle test, on the same kd-tree and the same
// robust traversal (cc/kdtree/traversal.h). The issue "Hard cases stay
// numerically stable" asks for this number next to the adversarial suite.
//
//   bazel build --config=opt //cc/robust:robust_cost_bench
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
// Timing: one thread; the two modes alternate within each of --repeats rounds
// (fast then watertight, then the other way round, ...), so load changes on a
// shared machine hit both;
// the fastest run of each is reported, every run is recorded.
// Output: one JSON line per preset and mode, appended to --out (stdout when
// empty): rays, seconds, rays/s, hits, and the number of rays whose answer
// differs between the two modes (hit versus miss or another triangle for
// primary rays, occlusion for shadow rays; same triangle at a t differing in
// the last bits is counted apart).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "cc/render/camera.h"
#include "cc/render/json.h"
#include "cc/render/manifest.h"
#include "cc/render/secondary_rays.h"
#include "cc/render/view.h"
#include "cc/robust/preset_check.h"

ABSL_FLAG(std::string, scene, "", "manifest scene (data/cache/scenes/index.json)");
ABSL_FLAG(std::string, mesh, "", "mesh file (default: a generated ~100k-triangle scene)");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups", "triangle-soup cache ('' = none)");
ABSL_FLAG(std::string, out, "", "JSON-lines output file (appended); stdout when empty");
ABSL_FLAG(std::string, presets, "", "comma-separated presets (default: default + the nine)");
ABSL_FLAG(int, width, 0, "image width (0: the view's)");
ABSL_FLAG(int, height, 0, "image height (0: the view's)");
ABSL_FLAG(int, repeats, 5, "timed rounds (both modes each); the fastest run is reported");

namespace kdtree {
namespace {

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

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      return std::string(absl::StripAsciiWhitespace(line.substr(line.find(':') + 1)));
    }
  }
  return "";
}

struct Trace {
  std::vector<double> runs;
  std::vector<Hit> primary;
  std::vector<char> shadow;
  double best() const { return *std::min_element(runs.begin(), runs.end()); }
};

void TraceOnce(const KdTree& tree, const std::vector<Ray>& primary, const std::vector<Ray>& shadow,
               IntersectionMode mode, Trace* out) {
  out->primary.resize(primary.size());
  out->shadow.resize(shadow.size());
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < primary.size(); ++i) out->primary[i] = Intersect(tree, primary[i], mode);
  for (size_t i = 0; i < shadow.size(); ++i) out->shadow[i] = Occluded(tree, shadow[i], mode);
  out->runs.push_back(Seconds(start));
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

int Run() {
  absl::StatusOr<Scene> scene = LoadScene();
  if (!scene.ok()) {
    std::fprintf(stderr, "robust_cost_bench: %s\n", scene.status().ToString().c_str());
    return 1;
  }
  const TriangleSoup& soup = scene->soup;
  std::vector<std::string> presets = robust::CheckedPresets();
  if (!absl::GetFlag(FLAGS_presets).empty()) {
    presets = absl::StrSplit(absl::GetFlag(FLAGS_presets), ',');
  }
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
  const std::string cpu = CpuModel();
  std::printf("%s: %zu triangles, %dx%d (%s view), %zu primary + %zu shadow rays, %d rounds, "
              "single thread\n",
              scene->name.c_str(), soup.size(), scene->view.width, scene->view.height,
              scene->view_source.c_str(), primary.size(), shadow.size(), repeats);
  std::printf("%-18s %10s %10s %12s %12s %8s %10s\n", "preset", "fast s", "robust s", "fast Mray/s",
              "robust Mray/s", "cost", "mismatch");
  std::FILE* out = stdout;
  if (!absl::GetFlag(FLAGS_out).empty()) {
    out = std::fopen(absl::GetFlag(FLAGS_out).c_str(), "a");
    if (out == nullptr) {
      std::fprintf(stderr, "robust_cost_bench: cannot open %s\n", absl::GetFlag(FLAGS_out).c_str());
      return 1;
    }
  }
  const size_t rays = primary.size() + shadow.size();
  for (const std::string& name : presets) {
    absl::StatusOr<Config> config = robust::ConfigFor(name);
    absl::StatusOr<KdTree> tree =
        config.ok() ? BuildKdTree(soup, *config) : absl::StatusOr<KdTree>(config.status());
    if (!tree.ok()) {
      std::fprintf(stderr, "robust_cost_bench: %s: %s\n", name.c_str(),
                   tree.status().ToString().c_str());
      return 1;
    }
    Trace fast, robust;
    for (int r = 0; r < repeats; ++r) {  // interleaved rounds, order alternating
      const bool fast_first = r % 2 == 0;
      TraceOnce(*tree, primary, shadow, fast_first ? IntersectionMode::kFast
                                                   : IntersectionMode::kWatertight,
                fast_first ? &fast : &robust);
      TraceOnce(*tree, primary, shadow, fast_first ? IntersectionMode::kWatertight
                                                   : IntersectionMode::kFast,
                fast_first ? &robust : &fast);
    }
    size_t mismatches = 0, other_t = 0;
    for (size_t i = 0; i < primary.size(); ++i) {
      const Hit &f = fast.primary[i], &w = robust.primary[i];
      mismatches += f.tri != w.tri;  // hit versus miss, or another triangle
      other_t += f.tri == w.tri && f.hit() && f.t != w.t;
    }
    for (size_t i = 0; i < shadow.size(); ++i) mismatches += fast.shadow[i] != robust.shadow[i];
    for (const Trace* t : {&fast, &robust}) {
      size_t primary_hits = 0, shadow_hits = 0;
      for (const Hit& h : t->primary) primary_hits += h.hit();
      for (char s : t->shadow) shadow_hits += s;
      std::vector<std::string> runs;
      for (double s : t->runs) runs.push_back(absl::StrFormat("%.6f", s));
      const std::string line = absl::StrFormat(
          "{\"scene\": %s, \"triangles\": %zu, \"view\": %s, \"width\": %d, \"height\": %d, "
          "\"preset\": %s, \"mode\": \"%s\", \"rays\": %zu, \"primary_rays\": %zu, "
          "\"shadow_rays\": %zu, \"seconds\": %.6f, \"runs\": [%s], \"rays_per_s\": %.1f, "
          "\"primary_hits\": %zu, \"shadow_hits\": %zu, \"mismatches_between_modes\": %zu, "
          "\"same_triangle_other_t\": %zu, \"build_seconds\": %.4f, \"threads\": 1, "
          "\"cpu\": %s}\n",
          JsonQuote(scene->name), soup.size(), JsonQuote(scene->view_source), scene->view.width,
          scene->view.height, JsonQuote(name), t == &fast ? "fast" : "watertight", rays,
          primary.size(), shadow.size(), t->best(), absl::StrJoin(runs, ", "),
          rays / t->best(), primary_hits, shadow_hits, mismatches, other_t,
          tree->build_seconds, JsonQuote(cpu));
      std::fputs(line.c_str(), out);
    }
    std::fflush(out);
    std::printf("%-18s %10.3f %10.3f %12.3f %12.3f %7.1f%% %10zu\n", name.c_str(), fast.best(),
                robust.best(), rays / fast.best() * 1e-6, rays / robust.best() * 1e-6,
                100.0 * (robust.best() / fast.best() - 1), mismatches);
    std::fflush(stdout);
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
