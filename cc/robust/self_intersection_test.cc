// Hard case 7: self-intersection. The same small scene (a ground quad, an
// occluder quad hovering 1e-4 above part of it, a closed icosphere and 40
// random tilted triangles) is placed at vertex magnitudes 1e-8, 1e-4, 1, 1e4
// and 1e8 (every coordinate times M, offset by about 1.6 M). From 24 points on
// every triangle (1500 on the ground and occluder quads' triangles), shadow
// rays to two point lights are spawned with
// SpawnShadowRay (cc/geometry/spawn.h: offset from the hit point's error
// bound). Required, for every preset, in watertight mode:
//  - a shadow ray never hits the triangle it was spawned from;
//  - any hit (Occluded) agrees with the closest hit within the light distance,
//    also when told the origin triangle (TraversalOptions::origin_tri, which
//    the watertight traversal then leaves untested);
//  - the kd-tree agrees with brute force (also in fast mode);
//  - every point under the occluder is in shadow (no real occluder skipped).
// Reported for comparison: the fast mode, no offset at all, and a fixed
// offset of 1e-4 along the normal (which skips the occluder at small scales
// and re-hits the surface at large ones).
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/geometry/spawn.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/traversal.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

constexpr double kGap = 1e-4;  // occluder height above the ground, in units of M

// The scene at unit scale (ground: triangles 0 and 1; occluder: 2 and 3).
TriangleSoup UnitScene() {
  TriangleSoup s;
  s.Add({-1, 0, -1}, {1, 0, -1}, {1, 0, 1});
  s.Add({-1, 0, -1}, {1, 0, 1}, {-1, 0, 1});
  const float g = static_cast<float>(kGap);
  s.Add({-0.6f, g, -0.5f}, {-0.1f, g, -0.5f}, {-0.1f, g, 0.5f});
  s.Add({-0.6f, g, -0.5f}, {-0.1f, g, 0.5f}, {-0.6f, g, 0.5f});
  const double centre[3] = {0.5, 0.3, 0.1};
  const TriangleSoup ball = Icosphere(3, 0.25, centre);
  s.v.insert(s.v.end(), ball.v.begin(), ball.v.end());
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> u(-1, 1), h(0.05f, 0.8f), d(-0.15f, 0.15f);
  for (int i = 0; i < 40; ++i) {
    const Vec3 a(u(rng), h(rng), u(rng));
    s.Add(a, a + Vec3(d(rng), d(rng), d(rng)), a + Vec3(d(rng), d(rng), d(rng)));
  }
  return s;
}

Vec3 Place(const Vec3& p, double m) {
  return Vec3(static_cast<float>((p.x + 1.3) * m), static_cast<float>((p.y + 0.6) * m),
              static_cast<float>((p.z - 0.9) * m));
}

struct Origin {
  uint32_t tri;
  BoundedPoint point;
  Vec3 normal;
  bool under_occluder;  // on the ground, below the occluder (must be shadowed by light 0)
};

TEST(SelfIntersection, ShadowRaysAtEveryMagnitude) {
  const TriangleSoup unit = UnitScene();
  for (double m : {1e-8, 1e-4, 1.0, 1e4, 1e8}) {
    TriangleSoup soup;
    for (const Vec3& p : unit.v) soup.v.push_back(Place(p, m));
    const Vec3 lights[2] = {Place(Vec3(0.1f, 2.0f, 0.2f), m), Place(Vec3(-1.5f, 0.3f, 1.2f), m)};
    // Points on every triangle.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u01(0, 1);
    std::vector<Origin> origins;
    for (uint32_t t = 0; t < soup.size(); ++t) {
      const Vec3 n = GeometricNormal(soup.a(t), soup.b(t), soup.c(t));
      const int samples = t < 4 ? 1500 : 24;  // dense on the ground and the occluder
      for (int k = 0; k < samples; ++k) {
        float bu = u01(rng), bv = u01(rng);
        if (bu + bv > 1) bu = 1 - bu, bv = 1 - bv;
        const BoundedPoint p = HitPointWithError(soup.a(t), soup.b(t), soup.c(t), bu, bv);
        // Unit-scale position of the point, to tell whether it is under the occluder.
        const double x = p.p.x / m - 1.3, z = p.p.z / m + 0.9;
        const bool under = t < 2 && x > -0.55 && x < -0.15 && z > -0.45 && z < 0.45;
        origins.push_back({t, p, n, under});
      }
    }
    std::vector<Ray> rays;  // shadow rays: origin i, light l at 2 i + l
    for (const Origin& o : origins) {
      for (const Vec3& light : lights) rays.push_back(SpawnShadowRay(o.point, o.normal, light));
    }
    const std::string case_name = absl::StrCat("self_intersection/", m);
    for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
      const bool required = mode == IntersectionMode::kWatertight;
      ExpectNoMismatches(case_name, CheckAllPresets(case_name, soup, rays, mode));
      for (const std::string& preset : CheckedPresets()) {
        absl::StatusOr<KdTree> tree = BuildKdTree(soup, *ConfigFor(preset));
        ASSERT_TRUE(tree.ok()) << tree.status();
        size_t self_hits = 0, any_vs_closest = 0, lit_under_occluder = 0, origin_skip = 0;
        TraversalOptions from_origin;
        from_origin.mode = mode;
        for (size_t i = 0; i < rays.size(); ++i) {
          const Origin& o = origins[i / 2];
          const Hit h = Intersect(*tree, rays[i], WithTest(mode));
          self_hits += h.hit() && h.tri == o.tri;
          any_vs_closest += Occluded(*tree, rays[i], WithTest(mode)) != h.hit();
          from_origin.origin_tri = o.tri;
          origin_skip += Occluded(*tree, rays[i], from_origin) != h.hit();
          lit_under_occluder += o.under_occluder && i % 2 == 0 && !h.hit();
        }
        std::printf("ROBUST_JSON {\"case\": \"%s\", \"preset\": \"%s\", \"mode\": \"%s\", "
                    "\"offset\": \"error_bound\", \"shadow_rays\": %zu, \"self_hits\": %zu, "
                    "\"any_vs_closest\": %zu, \"occluder_skipped\": %zu}\n",
                    case_name.c_str(), preset.c_str(), IntersectionModeName(mode), rays.size(),
                    self_hits, any_vs_closest, lit_under_occluder);
        EXPECT_EQ(any_vs_closest, 0u) << case_name << " " << preset;
        EXPECT_EQ(origin_skip, 0u) << case_name << " " << preset;
        if (required) {
          EXPECT_EQ(self_hits, 0u) << case_name << " " << preset;
          EXPECT_EQ(lit_under_occluder, 0u) << case_name << " " << preset;
        }
      }
    }
    // For comparison (default preset, watertight): no offset, and a fixed 1e-4.
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
    ASSERT_TRUE(tree.ok());
    for (const char* method : {"none", "fixed_1e-4"}) {
      size_t self_hits = 0, lit_under_occluder = 0;
      for (size_t i = 0; i < origins.size(); ++i) {
        const Origin& o = origins[i];
        for (int l = 0; l < 2; ++l) {
          Vec3 origin = o.point.p;
          if (std::string(method) != "none") {
            const float side = Dot(lights[l] - o.point.p, o.normal) >= 0 ? 1e-4f : -1e-4f;
            origin = origin + o.normal * side;
          }
          const Ray ray{origin, lights[l] - origin, 0.0f, 1.0f};
          const Hit h = Intersect(*tree, ray);
          self_hits += h.hit() && h.tri == o.tri;
          lit_under_occluder += o.under_occluder && l == 0 && !h.hit();
        }
      }
      std::printf("ROBUST_JSON {\"case\": \"%s\", \"preset\": \"default\", \"mode\": "
                  "\"watertight\", \"offset\": \"%s\", \"shadow_rays\": %zu, \"self_hits\": %zu, "
                  "\"occluder_skipped\": %zu}\n",
                  case_name.c_str(), method, 2 * origins.size(), self_hits, lit_under_occluder);
    }
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
