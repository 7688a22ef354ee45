// What robustness costs in render time: the same rays traced by every preset
// with the fast (Moeller-Trumbore) and the watertight (Woop et al. 2013)
// triangle test, on the same kd-tree and the same (robust) traversal.
//
//   bazel run --config=opt //cc/robust:robust_cost_bench -- --out FILE [--mesh PATH]
//
// Scene: --mesh (anything cc/io/mesh_loader.h reads), or a generated one of
// about 100k triangles (a closed bumpy sphere of 81,920 triangles standing on
// a voxel terrain). Rays: the primary rays of a --width x --height pinhole
// camera (closest hit), then one shadow ray per primary hit to a point light
// (any hit), spawned with SpawnShadowRay (cc/geometry/spawn.h) from the
// watertight hits, so both modes trace exactly the same rays. Single thread;
// each measurement is the fastest of --repeats. One JSON line per preset and
// mode goes to --out: rays, seconds, rays/s, hits, and the number of rays
// whose answer differs between the two modes (hit versus miss or another
// triangle for primary rays, occlusion for shadow rays; same triangle at a t
// differing in the last bits is counted apart).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "cc/geometry/spawn.h"
#include "cc/io/mesh_loader.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "cc/robust/preset_check.h"

ABSL_FLAG(std::string, mesh, "", "mesh file (default: a generated ~100k-triangle scene)");
ABSL_FLAG(std::string, out, "", "JSON-lines output file (appended); stdout when empty");
ABSL_FLAG(std::string, presets, "", "comma-separated presets (default: default + the nine)");
ABSL_FLAG(int, width, 1024, "image width");
ABSL_FLAG(int, height, 768, "image height");
ABSL_FLAG(int, repeats, 3, "timed runs per preset and mode; the fastest is reported");

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

struct Trace {
  double seconds = 1e300;
  std::vector<Hit> primary;
  std::vector<char> shadow;
};

Trace TraceAll(const KdTree& tree, const std::vector<Ray>& primary,
               const std::vector<Ray>& shadow, IntersectionMode mode, int repeats) {
  Trace out;
  out.primary.resize(primary.size());
  out.shadow.resize(shadow.size());
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    for (size_t i = 0; i < primary.size(); ++i) out.primary[i] = Intersect(tree, primary[i], mode);
    for (size_t i = 0; i < shadow.size(); ++i) out.shadow[i] = Occluded(tree, shadow[i], mode);
    out.seconds = std::min(out.seconds, Seconds(start));
  }
  return out;
}

int Run() {
  TriangleSoup soup;
  std::string scene = "generated";
  const std::string mesh = absl::GetFlag(FLAGS_mesh);
  if (!mesh.empty()) {
    absl::StatusOr<TriangleSoup> loaded = LoadMesh(mesh);
    if (!loaded.ok()) {
      std::fprintf(stderr, "%s\n", loaded.status().ToString().c_str());
      return 1;
    }
    soup = *std::move(loaded);
    scene = mesh.substr(mesh.find_last_of('/') + 1);
  } else {
    soup = GeneratedScene();
  }
  std::vector<std::string> presets = robust::CheckedPresets();
  if (!absl::GetFlag(FLAGS_presets).empty()) {
    presets = absl::StrSplit(absl::GetFlag(FLAGS_presets), ',');
  }
  const int repeats = std::max(1, absl::GetFlag(FLAGS_repeats));
  const std::vector<Ray> primary =
      testing::CameraRays(soup, absl::GetFlag(FLAGS_width), absl::GetFlag(FLAGS_height));
  // Shadow rays from the watertight hits of the default tree.
  std::vector<Ray> shadow;
  {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
    if (!tree.ok()) {
      std::fprintf(stderr, "%s\n", tree.status().ToString().c_str());
      return 1;
    }
    const AABB box = soup.Bounds();
    const Vec3 ext = box.Extent();
    const Vec3 light = (box.lo + box.hi) * 0.5f + Vec3(0.6f * ext.x, 1.5f * ext.y, 0.8f * ext.z);
    for (const Ray& ray : primary) {
      const Hit h = Intersect(*tree, ray);
      if (!h.hit()) continue;
      const Vec3 &a = soup.a(h.tri), &b = soup.b(h.tri), &c = soup.c(h.tri);
      shadow.push_back(SpawnShadowRay(HitPointWithError(a, b, c, h.u, h.v),
                                      GeometricNormal(a, b, c), light));
    }
  }
  std::printf("%s: %zu triangles, %zu primary + %zu shadow rays, %d repeats, single thread\n",
              scene.c_str(), soup.size(), primary.size(), shadow.size(), repeats);
  std::printf("%-18s %10s %10s %12s %12s %8s %10s\n", "preset", "fast s", "robust s", "fast Mray/s",
              "robust Mray/s", "cost", "mismatch");
  std::FILE* out = stdout;
  if (!absl::GetFlag(FLAGS_out).empty()) {
    out = std::fopen(absl::GetFlag(FLAGS_out).c_str(), "a");
    if (out == nullptr) {
      std::fprintf(stderr, "cannot open %s\n", absl::GetFlag(FLAGS_out).c_str());
      return 1;
    }
  }
  const size_t rays = primary.size() + shadow.size();
  for (const std::string& name : presets) {
    absl::StatusOr<Config> config = robust::ConfigFor(name);
    absl::StatusOr<KdTree> tree =
        config.ok() ? BuildKdTree(soup, *config) : absl::StatusOr<KdTree>(config.status());
    if (!tree.ok()) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), tree.status().ToString().c_str());
      return 1;
    }
    const Trace fast = TraceAll(*tree, primary, shadow, IntersectionMode::kFast, repeats);
    const Trace robust = TraceAll(*tree, primary, shadow, IntersectionMode::kWatertight, repeats);
    size_t mismatches = 0, other_t = 0;
    for (size_t i = 0; i < primary.size(); ++i) {
      const Hit &f = fast.primary[i], &w = robust.primary[i];
      mismatches += f.tri != w.tri;  // hit versus miss, or another triangle
      other_t += f.tri == w.tri && f.hit() && f.t != w.t;
    }
    for (size_t i = 0; i < shadow.size(); ++i) mismatches += fast.shadow[i] != robust.shadow[i];
    for (const auto* t : {&fast, &robust}) {
      const bool is_fast = t == &fast;
      size_t primary_hits = 0, shadow_hits = 0;
      for (const Hit& h : t->primary) primary_hits += h.hit();
      for (char s : t->shadow) shadow_hits += s;
      std::fprintf(out,
                   "{\"scene\": \"%s\", \"triangles\": %zu, \"preset\": \"%s\", \"mode\": \"%s\", "
                   "\"rays\": %zu, \"primary_rays\": %zu, \"shadow_rays\": %zu, \"seconds\": "
                   "%.6f, \"rays_per_s\": %.1f, \"primary_hits\": %zu, \"shadow_hits\": %zu, "
                   "\"mismatches_between_modes\": %zu, \"same_triangle_other_t\": %zu, "
                   "\"build_seconds\": %.4f}\n",
                   scene.c_str(), soup.size(), name.c_str(), is_fast ? "fast" : "watertight",
                   rays, primary.size(), shadow.size(), t->seconds, rays / t->seconds,
                   primary_hits, shadow_hits, mismatches, other_t, tree->build_seconds);
    }
    std::fflush(out);
    std::printf("%-18s %10.3f %10.3f %12.3f %12.3f %7.1f%% %10zu\n", name.c_str(), fast.seconds,
                robust.seconds, rays / fast.seconds * 1e-6, rays / robust.seconds * 1e-6,
                100.0 * (robust.seconds / fast.seconds - 1), mismatches);
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
