// Hard case 5: watertightness. A closed icosphere of 81,920 triangles, at the
// origin (radius 1) and at an offset of 1.5e5 on every axis (radius 10, where a
// float step is 1/64), traced from inside:
//  - 16 origins (the centre and 15 random points within half the radius), 2^16
//    random directions each: 1,048,576 rays for the default preset; the first 2
//    origins (131,072 rays) for the nine report presets;
//  - from the centre and from one off-centre origin, one ray aimed exactly at
//    every vertex (40,962) and every edge midpoint (122,880): 327,684 rays for
//    the default preset, the 163,842 from the centre for the nine others.
// In watertight mode every ray must hit (miss rate 0). Every preset is also
// compared with brute force in both modes (0 mismatches); the fast mode's
// misses are reported. The brute force runs on exact candidate lists
// (cone_reference.h), checked against the full brute force on a sample.
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/robust/cone_reference.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

struct SphereCase {
  const char* name;
  double radius;
  double centre[3];
};

constexpr int kOrigins = 16;
constexpr int kDirections = 1 << 16;
constexpr int kPresetOrigins = 2;  // origins traced by the nine report presets

class WatertightSphere : public ::testing::TestWithParam<SphereCase> {};

TEST_P(WatertightSphere, EveryRayFromInsideHits) {
  const SphereCase c = GetParam();
  const TriangleSoup soup = Icosphere(6, c.radius, c.centre);
  ASSERT_EQ(soup.size(), 81920u);
  const BruteForce bf(soup);
  std::mt19937 rng(2024);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0, 1);
  // Origins: the centre, then random points within half the radius.
  std::vector<Vec3> origins = {Vec3(static_cast<float>(c.centre[0]),
                                    static_cast<float>(c.centre[1]),
                                    static_cast<float>(c.centre[2]))};
  while (origins.size() < kOrigins) {
    const double x = gauss(rng), y = gauss(rng), z = gauss(rng);
    const double s = 0.5 * c.radius * std::cbrt(unit(rng)) / std::sqrt(x * x + y * y + z * z);
    origins.emplace_back(static_cast<float>(c.centre[0] + s * x),
                         static_cast<float>(c.centre[1] + s * y),
                         static_cast<float>(c.centre[2] + s * z));
  }
  // Rays: random directions per origin, then the aimed rays.
  std::vector<Ray> rays;
  std::vector<int> origin_of;
  for (int o = 0; o < kOrigins; ++o) {
    for (int i = 0; i < kDirections; ++i) {
      const double x = gauss(rng), y = gauss(rng), z = gauss(rng);
      const double l = std::sqrt(x * x + y * y + z * z);
      rays.push_back(Ray{origins[o], Vec3(static_cast<float>(x / l), static_cast<float>(y / l),
                                          static_cast<float>(z / l))});
      origin_of.push_back(o);
    }
  }
  const size_t n_random = rays.size();
  const std::vector<Vec3> vertices = UniqueVertices(soup), midpoints = EdgeMidpoints(soup);
  ASSERT_EQ(vertices.size(), 40962u);
  ASSERT_EQ(midpoints.size(), 122880u);
  for (int o = 0; o < 2; ++o) {
    for (const std::vector<Vec3>* targets : {&vertices, &midpoints}) {
      for (const Vec3& p : *targets) {
        rays.push_back(Ray{origins[o], p - origins[o]});
        origin_of.push_back(o);
      }
    }
  }
  const size_t n_aimed = rays.size() - n_random;
  // Exact references on candidate lists.
  std::vector<std::unique_ptr<ConeReference>> cones;
  for (const Vec3& o : origins) {
    absl::StatusOr<ConeReference> cone = ConeReference::Make(soup, o, 8);
    ASSERT_TRUE(cone.ok()) << cone.status();
    cones.push_back(std::make_unique<ConeReference>(*std::move(cone)));
  }
  std::printf("%s: %zu triangles, %zu random rays from %d origins, %zu aimed rays, %.1f candidates "
              "per direction cell\n",
              c.name, soup.size(), n_random, kOrigins, n_aimed, cones[0]->MeanCandidates());
  std::fflush(stdout);
  // The sample (preset_check.h RayStride(): every ray unless a quick
  // reproduction asks for fewer); default gets all of it, the other presets
  // the rays of the first origins.
  std::vector<size_t> all, small;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (!InSample(i)) continue;
    all.push_back(i);
    if (origin_of[i] < (i < n_random ? kPresetOrigins : 1)) small.push_back(i);
  }
  std::vector<Ray> all_rays, small_rays;
  for (size_t i : all) all_rays.push_back(rays[i]);
  for (size_t i : small) small_rays.push_back(rays[i]);

  std::vector<std::string> presets = CheckedPresets();
  std::vector<KdTree> trees;
  for (const std::string& name : presets) {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, *ConfigFor(name));
    ASSERT_TRUE(tree.ok()) << tree.status();
    trees.push_back(*std::move(tree));
  }
  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    const char* mode_name = IntersectionModeName(mode);
    std::vector<Hit> reference(rays.size());  // filled on the sample
    ParallelFor(all.size(), [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        const size_t i = all[k];
        reference[i] = cones[origin_of[i]]->Intersect(bf, rays[i], mode);
      }
    });
    // The candidate lists lose nothing: full brute force on a sample.
    int sample_mismatch = 0;
    for (size_t k = 0; k < all.size(); k += 997) {
      const size_t i = all[k];
      const Hit full = bf.Intersect(rays[i], mode);
      sample_mismatch += full.tri != reference[i].tri || (full.hit() && full.t != reference[i].t);
    }
    EXPECT_EQ(sample_mismatch, 0) << mode_name << ": candidate lists disagree with brute force";
    size_t random = 0, vertex = 0, edge = 0, miss_random = 0, miss_vertex = 0, miss_edge = 0;
    for (size_t i : all) {
      const bool miss = !reference[i].hit();
      if (i < n_random) {
        ++random;
        miss_random += miss;
      } else if ((i - n_random) % (vertices.size() + midpoints.size()) < vertices.size()) {
        ++vertex;
        miss_vertex += miss;
      } else {
        ++edge;
        miss_edge += miss;
      }
    }
    std::printf("ROBUST_JSON {\"case\": \"watertight_sphere/%s\", \"mode\": \"%s\", "
                "\"random_rays\": %zu, \"random_misses\": %zu, \"vertex_rays\": %zu, "
                "\"vertex_misses\": %zu, \"edge_midpoint_rays\": %zu, \"edge_midpoint_misses\": "
                "%zu}\n",
                c.name, mode_name, random, miss_random, vertex, miss_vertex, edge, miss_edge);
    if (mode == IntersectionMode::kWatertight) {
      EXPECT_EQ(miss_random + miss_vertex + miss_edge, 0u) << "the watertight test must not miss";
    }
    std::vector<Hit> all_reference;
    for (size_t i : all) all_reference.push_back(reference[i]);
    std::vector<Hit> small_reference;
    for (size_t i : small) small_reference.push_back(reference[i]);
    std::vector<CheckResult> results;
    for (size_t p = 0; p < presets.size(); ++p) {
      const bool everything = presets[p] == "default";
      CheckResult r = everything ? CheckTree(trees[p], all_rays, all_reference, mode)
                                 : CheckTree(trees[p], small_rays, small_reference, mode);
      r.preset = presets[p];
      std::printf("ROBUST_JSON %s\n",
                  ResultJson(std::string("watertight_sphere/") + c.name, r).c_str());
      std::fflush(stdout);
      results.push_back(std::move(r));
    }
    ExpectNoMismatches(std::string("watertight_sphere/") + c.name, results);
  }
}

INSTANTIATE_TEST_SUITE_P(Spheres, WatertightSphere,
                         ::testing::Values(SphereCase{"origin", 1.0, {0, 0, 0}},
                                           SphereCase{"offset", 10.0, {1.5e5, 1.5e5, 1.5e5}}),
                         [](const ::testing::TestParamInfo<SphereCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace robust
}  // namespace kdtree
