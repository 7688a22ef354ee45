// Every preset against the brute-force reference in the same intersection
// mode: closest hit (triangle, or t within 1e-6 relative where two triangles
// tie) and any hit, per scene. Watertight mode (the default): 100k seeded
// random rays plus every ray of an 800x800 camera; fast mode (Moeller-Trumbore):
// the first 5k of the random rays plus every 8th camera row (100 rows).
#include "cc/kdtree/traversal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/io/mesh_loader.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/stats.h"
#include "cc/kdtree/test_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

constexpr size_t kFastRandomRays = 5000;
constexpr int kFastRowStep = 8;

struct Scene {
  TriangleSoup soup;
  std::vector<Ray> rays;       // n_random random rays, then the camera rays
  size_t n_random = 0;
  std::vector<Hit> reference;  // brute force closest hits, watertight
  std::vector<Hit> reference_fast;  // fast mode; set only for the rays UsedIn() it
  bool UsedIn(IntersectionMode mode, size_t i) const {
    return mode == IntersectionMode::kWatertight || i < kFastRandomRays ||
           (i >= n_random && (i - n_random) / 800 % kFastRowStep == 0);
  }
};

TriangleSoup MakeSoup(const std::string& name) {
  if (name == "bunny") {
    // The Stanford bunny when the scene library is present (experiments/test.sh
    // passes --test_env=KDTREE_SCENES=.../data/cache/scenes), else a generated
    // closed mesh of similar size.
    const char* dir = std::getenv("KDTREE_SCENES");
    if (dir != nullptr) {
      absl::StatusOr<TriangleSoup> bunny = LoadMesh(std::string(dir) + "/bunny.obj");
      if (bunny.ok()) {
        std::printf("bunny: the Stanford bunny, %zu triangles\n", bunny->size());
        return *std::move(bunny);
      }
      std::printf("bunny: %s; using a generated closed mesh\n", bunny.status().ToString().c_str());
    }
    return testing::BumpySphere(6, 11);  // 81,920 triangles
  }
  if (name == "sphere") return testing::BumpySphere(4, 1);  // 5,120 triangles
  if (name == "voxels") return testing::VoxelGrid(14, 8, 14, 2);
  if (name == "thin") return testing::ThinSoup(3000, 3);
  if (name == "flat") return testing::FlatScene(2000, 4);
  if (name == "tiny") {  // hand-made: shared edge, a triangle in a split plane, a sliver
    TriangleSoup s;
    s.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    s.Add({1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    s.Add({0.5f, 0, -1}, {0.5f, 1, -1}, {0.5f, 0, 1});
    s.Add({0, 0, 0.5f}, {1, 1, 0.5f}, {1, 1.0001f, 0.5f});
    s.Add({-1, -1, -1}, {2, -1, -1}, {-1, 2, 2});
    return s;
  }
  return {};
}

const Scene& GetScene(const std::string& name) {
  static auto* cache = new std::map<std::string, Scene>();
  auto it = cache->find(name);
  if (it != cache->end()) return it->second;
  Scene& s = (*cache)[name];
  s.soup = MakeSoup(name);
  s.rays = testing::RandomRays(s.soup, 100000, 17);
  const std::vector<Ray> cam = testing::CameraRays(s.soup, 800, 800);
  s.rays.insert(s.rays.end(), cam.begin(), cam.end());
  BruteForce bf(s.soup);
  const size_t n_random = s.rays.size() - cam.size();
  s.n_random = n_random;
  s.reference.resize(s.rays.size());
  s.reference_fast.resize(s.rays.size());
  // Random rays: every triangle, on all cores.
  const unsigned workers = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < workers; ++w) {
    pool.emplace_back([&, w] {
      for (size_t i = w; i < n_random; i += workers) {
        s.reference[i] = bf.Intersect(s.rays[i], IntersectionMode::kWatertight);
        if (i < kFastRandomRays) {
          s.reference_fast[i] = bf.Intersect(s.rays[i], IntersectionMode::kFast);
        }
      }
    });
  }
  for (std::thread& t : pool) t.join();
  // Camera rays: the rays of one image row lie in one plane through the eye,
  // so only triangles that reach that plane (with a generous margin for the
  // rounding of the ray directions) can be hit; the reference tests all of them.
  const AABB box = s.soup.Bounds();
  const double margin = 1e-4 * (Length(box.Extent()) + Length(cam[0].origin - box.lo));
  std::vector<uint32_t> candidates;
  for (int row = 0; row < 800; ++row) {
    const Ray& first = cam[row * 800];
    const Ray& last = cam[row * 800 + 799];
    const double n[3] = {
        double(first.dir.y) * last.dir.z - double(first.dir.z) * last.dir.y,
        double(first.dir.z) * last.dir.x - double(first.dir.x) * last.dir.z,
        double(first.dir.x) * last.dir.y - double(first.dir.y) * last.dir.x};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    candidates.clear();
    for (size_t t = 0; t < s.soup.size(); ++t) {
      double lo = 1e300, hi = -1e300;
      for (const Vec3* v : {&s.soup.a(t), &s.soup.b(t), &s.soup.c(t)}) {
        const double d = ((v->x - double(first.origin.x)) * n[0] + (v->y - double(first.origin.y)) * n[1] +
                          (v->z - double(first.origin.z)) * n[2]) / len;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      if (lo <= margin && hi >= -margin) candidates.push_back(static_cast<uint32_t>(t));
    }
    for (int x = 0; x < 800; ++x) {
      const size_t i = n_random + row * 800 + x;
      s.reference[i] = bf.Intersect(s.rays[i], candidates, IntersectionMode::kWatertight);
      if (row % kFastRowStep == 0) {
        s.reference_fast[i] = bf.Intersect(s.rays[i], candidates, IntersectionMode::kFast);
      }
    }
  }
  return s;
}

class VsBruteForce
    : public ::testing::TestWithParam<std::tuple<std::string, std::string, IntersectionMode>> {};

TEST_P(VsBruteForce, EveryRayAgrees) {
  const auto& [scene_name, preset, mode] = GetParam();
  const Scene& scene = GetScene(scene_name);
  ASSERT_FALSE(scene.soup.empty());
  absl::StatusOr<Config> config = Preset(preset);
  ASSERT_TRUE(config.ok()) << config.status();
  absl::StatusOr<KdTree> tree = BuildKdTree(scene.soup, *config);
  ASSERT_TRUE(tree.ok()) << tree.status();
  const TreeStats stats = ComputeStats(*tree);
  EXPECT_EQ(stats.invalid_leaf_boxes, 0u);
  EXPECT_EQ(stats.lost_planar, 0u);

  int closest_mismatch = 0, any_mismatch = 0, hits = 0;
  size_t rays = 0;
  TraversalCounters counters;
  const std::vector<Hit>& reference =
      mode == IntersectionMode::kWatertight ? scene.reference : scene.reference_fast;
  for (size_t i = 0; i < scene.rays.size(); ++i) {
    if (!scene.UsedIn(mode, i)) continue;
    ++rays;
    const Ray& ray = scene.rays[i];
    const Hit& want = reference[i];
    const Hit got = mode == IntersectionMode::kWatertight ? Intersect(*tree, ray, {}, &counters)
                                                          : Intersect(*tree, ray, WithTest(mode), &counters);
    hits += want.hit();
    bool same = got.hit() == want.hit();
    if (same && want.hit() && got.tri != want.tri) {
      same = std::fabs(got.t - want.t) <= 1e-6f * std::fmax(1.0f, std::fabs(want.t));
    }
    if (!same && ++closest_mismatch <= 5) {
      ADD_FAILURE() << "ray " << i << ": kd-tree tri " << got.tri << " t " << got.t
                    << ", brute force tri " << want.tri << " t " << want.t;
    }
    if (Occluded(*tree, ray, WithTest(mode)) != want.hit() && ++any_mismatch <= 5) {
      ADD_FAILURE() << "ray " << i << ": any-hit disagrees with brute-force closest hit";
    }
  }
  EXPECT_EQ(closest_mismatch, 0);
  EXPECT_EQ(any_mismatch, 0);
  EXPECT_GT(hits, static_cast<int>(rays / 40)) << "the rays should hit the scene";
  EXPECT_EQ(counters.rays, rays);
  std::printf("%s/%s/%s: %zu rays, %d hits, N_IT %.2f, N_TR %.2f, %s\n", scene_name.c_str(),
              preset.c_str(), IntersectionModeName(mode), rays, hits,
              static_cast<double>(counters.triangle_tests) / counters.rays,
              static_cast<double>(counters.inner_visits) / counters.rays,
              StatsToJson(stats).dump().c_str());
}

INSTANTIATE_TEST_SUITE_P(
    AllPresets, VsBruteForce,
    ::testing::Combine(::testing::Values("bunny", "sphere", "voxels", "thin", "flat", "tiny"),
                       ::testing::ValuesIn(AllPresetNames()),
                       ::testing::Values(IntersectionMode::kWatertight, IntersectionMode::kFast)),
    [](const ::testing::TestParamInfo<VsBruteForce::ParamType>& info) {
      std::string name = absl::StrCat(std::get<0>(info.param), "_", std::get<1>(info.param), "_",
                                      IntersectionModeName(std::get<2>(info.param)));
      for (char& c : name) if (c == '-') c = '_';
      return name;
    });

TEST(Traversal, EmptyTreeMissesEverything) {
  absl::StatusOr<KdTree> tree = BuildKdTree(TriangleSoup(), Config());
  ASSERT_TRUE(tree.ok());
  EXPECT_FALSE(Intersect(*tree, Ray{{0, 0, 0}, {1, 0, 0}}).hit());
  EXPECT_FALSE(Occluded(*tree, Ray{{0, 0, 0}, {1, 0, 0}}));
}

TEST(Traversal, NanRayIsAMiss) {
  absl::StatusOr<KdTree> tree = BuildKdTree(testing::BumpySphere(1, 1), Config());
  ASSERT_TRUE(tree.ok());
  const float nan = std::nanf(""), inf = INFINITY;
  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    for (const Ray& bad : {Ray{{nan, 0, 0}, {1, 0, 0}}, Ray{{-5, 0, 0}, {nan, 0, 0}},
                           Ray{{-inf, 0, 0}, {1, 0, 0}}, Ray{{-5, 0, 0}, {inf, 0, 0}},
                           Ray{{-5, 0, 0}, {0, 0, 0}}, Ray{{-5, 0, 0}, {1, 0, 0}, nan, inf},
                           Ray{{-5, 0, 0}, {1, 0, 0}, 0, nan}}) {
      EXPECT_FALSE(Intersect(*tree, bad, WithTest(mode)).hit());
      EXPECT_FALSE(Occluded(*tree, bad, WithTest(mode)));
    }
    EXPECT_TRUE(Intersect(*tree, Ray{{-5, 0, 0}, {1, 0, 0}}, WithTest(mode)).hit());
  }
}

TEST(Traversal, DefaultIsWatertight) {
  // 400 pairs of triangles, each pair sharing an edge, on a grid; rays through
  // points of each shared edge: the default (watertight) hits every time, the
  // fast test misses some.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  TriangleSoup s;
  std::vector<Ray> rays;
  for (int gx = 0; gx < 20; ++gx) {
    for (int gy = 0; gy < 20; ++gy) {
      const Vec3 centre(10.0f * gx, 10.0f * gy, 5);
      const Vec3 p = centre + Vec3(u(rng), u(rng), u(rng));
      const Vec3 q = centre + Vec3(u(rng), u(rng), u(rng));
      const Vec3 r1 = centre + Vec3(u(rng), u(rng), u(rng)), r2 = p + q - r1;
      s.Add(p, q, r1);
      s.Add(q, p, r2);
      for (int k = 1; k < 16; ++k) {
        const Vec3 target = p + (q - p) * (k / 16.0f);
        const Vec3 origin = centre + Vec3(0.3f * u(rng), 0.3f * u(rng), -5 + u(rng));
        rays.push_back(Ray{origin, target - origin});
      }
    }
  }
  absl::StatusOr<KdTree> tree = BuildKdTree(s, Config());
  ASSERT_TRUE(tree.ok());
  int fast_misses = 0;
  const BruteForce bf(s);
  for (const Ray& ray : rays) {
    EXPECT_TRUE(Intersect(*tree, ray).hit())
        << "brute force " << bf.Intersect(ray).hit() << ", origin " << ray.origin.x << " "
        << ray.origin.y << " " << ray.origin.z << ", dir " << ray.dir.x << " " << ray.dir.y << " "
        << ray.dir.z;
    EXPECT_TRUE(Occluded(*tree, ray));
    fast_misses += !Intersect(*tree, ray, WithTest(IntersectionMode::kFast)).hit();
  }
  EXPECT_GT(fast_misses, 0) << "the fast test should miss some of these";
  std::printf("shared edges: fast mode misses %d of %zu rays, watertight 0\n", fast_misses,
              rays.size());
}

TEST(Traversal, ShadowRayStopsAtTmax) {
  TriangleSoup s;
  s.Add({-1, -1, 5}, {1, -1, 5}, {0, 1, 5});
  absl::StatusOr<KdTree> tree = BuildKdTree(s, Config());
  ASSERT_TRUE(tree.ok());
  EXPECT_TRUE(Occluded(*tree, Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 6.0f}));
  EXPECT_FALSE(Occluded(*tree, Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 4.0f}));
  const Hit h = Intersect(*tree, Ray{{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(h.hit());
  EXPECT_FLOAT_EQ(h.t, 5.0f);
}

}  // namespace
}  // namespace kdtree
