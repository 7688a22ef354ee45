// Hard case 8: degenerate and garbage triangles mixed into a real mesh (a
// closed bumpy sphere of 5,120 triangles): NaN, +-Inf and absurd (1e31, 3e38)
// coordinates, repeated vertices, all three vertices equal, exactly collinear
// vertices, and thin but valid slivers, interleaved at random positions.
//  - The raw soup is refused by the builder (non-finite vertex), not crashed on.
//  - CleanSoup (the loader's rules) drops exactly the garbage, with counts.
//  - Every preset builds on the cleaned soup and matches brute force on a
//    200x200 camera, random rays and rays aimed at every garbage triangle's
//    finite vertices and centroid, in both modes; no hit has a NaN t, u or v
//    and no pixel of a shaded 200x200 image is NaN.
//  - Kept in the tree instead (only the non-finite ones removed), the
//    degenerate triangles: the build succeeds and, in watertight mode, they
//    are never hit (the test rejects exactly zero-area triangles, which the
//    shear could otherwise round apart into a hittable sliver); the fast
//    mode's count is reported.
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cc/geometry/spawn.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/soup_cleaner.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

struct Dirty {
  TriangleSoup soup;
  std::set<uint32_t> nonfinite, degenerate;  // indices into soup
  std::vector<Vec3> aim;                     // finite points of the garbage
};

Dirty MakeDirty() {
  const TriangleSoup mesh = testing::BumpySphere(4, 1);
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u(0, 1);
  const float nan = std::nanf(""), inf = INFINITY;
  // Kind 0: non-finite or absurd, 1: zero area, 2: a valid sliver.
  std::vector<std::pair<int, std::vector<Vec3>>> garbage;
  auto vertex = [&]() { return mesh.v[rng() % mesh.v.size()]; };
  for (int i = 0; i < 12; ++i) {
    const Vec3 a = vertex(), b = vertex();
    garbage.push_back({0, {a, b, Vec3(nan, a.y, a.z)}});
    garbage.push_back({0, {Vec3(a.x, i % 2 ? inf : -inf, a.z), a, b}});
    garbage.push_back({0, {a, Vec3(i % 2 ? 1e31f : -3e38f, b.y, b.z), b}});
  }
  for (int i = 0; i < 20; ++i) {
    const Vec3 a = vertex(), b = vertex();
    garbage.push_back({1, {a, a, b}});  // repeated vertex
    // Exactly collinear: dyadic points, so p + d and p + 2 d are exact.
    const Vec3 p(std::round(a.x * 1024) / 1024, std::round(a.y * 1024) / 1024,
                 std::round(a.z * 1024) / 1024);
    const Vec3 d(0.25f * (u(rng) - 0.5f), 0.125f, -0.0625f);
    const Vec3 dq(std::round(d.x * 1024) / 1024, d.y, d.z);
    garbage.push_back({1, {p, p + dq, p + dq * 2.0f}});
    // A thin but valid sliver: kept.
    garbage.push_back({2, {a, b, (a + b) * 0.5f + Vec3(1e-4f, -1e-4f, 2e-4f)}});
  }
  for (int i = 0; i < 10; ++i) {
    const Vec3 a = vertex();
    garbage.push_back({1, {a, a, a}});
  }
  // Interleave: each garbage triangle goes after a random mesh triangle.
  std::vector<std::vector<int>> after(mesh.size());
  for (size_t g = 0; g < garbage.size(); ++g) after[rng() % mesh.size()].push_back(g);
  Dirty d;
  for (size_t t = 0; t < mesh.size(); ++t) {
    d.soup.Add(mesh.a(t), mesh.b(t), mesh.c(t));
    for (int g : after[t]) {
      const auto& [kind, v] = garbage[g];
      const uint32_t index = static_cast<uint32_t>(d.soup.size());
      d.soup.Add(v[0], v[1], v[2]);
      if (kind == 0) d.nonfinite.insert(index);
      if (kind == 1) d.degenerate.insert(index);
      for (const Vec3& p : v) {
        if (IsFinite(p) && std::fabs(p.x) < 1e30f && std::fabs(p.y) < 1e30f &&
            std::fabs(p.z) < 1e30f) {
          d.aim.push_back(p);
        }
      }
      if (kind != 0) d.aim.push_back((v[0] + v[1] + v[2]) / 3.0f);
    }
  }
  return d;
}

std::vector<Ray> AimedRays(const std::vector<Vec3>& targets) {
  const Vec3 origins[] = {{0, 0, 5}, {4, 1, -3}, {-3, -4, 1}, {0.05f, 0.02f, 0.01f}};
  std::vector<Ray> rays;
  for (const Vec3& o : origins) {
    for (const Vec3& p : targets) rays.push_back(Ray{o, p - o});
  }
  return rays;
}

TEST(Garbage, DroppedCountedNeverHitNoNan) {
  const Dirty dirty = MakeDirty();
  // The raw soup: refused with a message, never a crash.
  absl::StatusOr<KdTree> raw = BuildKdTree(dirty.soup, Config());
  ASSERT_FALSE(raw.ok());
  EXPECT_EQ(raw.status().code(), absl::StatusCode::kInvalidArgument) << raw.status();
  // Cleaned.
  CleanReport report;
  const TriangleSoup clean = CleanSoup(dirty.soup, &report);
  EXPECT_EQ(report.dropped_nonfinite, dirty.nonfinite.size());
  EXPECT_EQ(report.dropped_degenerate, dirty.degenerate.size());
  EXPECT_EQ(report.kept, dirty.soup.size() - dirty.nonfinite.size() - dirty.degenerate.size());
  for (uint32_t original : report.original_index) {
    EXPECT_EQ(dirty.nonfinite.count(original) + dirty.degenerate.count(original), 0u);
  }
  std::printf("ROBUST_JSON {\"case\": \"garbage/clean\", \"input_triangles\": %zu, \"kept\": %zu, "
              "\"dropped_nonfinite\": %zu, \"dropped_degenerate\": %zu}\n",
              dirty.soup.size(), report.kept, report.dropped_nonfinite, report.dropped_degenerate);
  std::vector<Ray> rays = testing::CameraRays(clean, 200, 200);
  const size_t pixels = rays.size();
  const std::vector<Ray> random = testing::RandomRays(clean, 20000, 7);
  rays.insert(rays.end(), random.begin(), random.end());
  const std::vector<Ray> aimed = AimedRays(dirty.aim);
  rays.insert(rays.end(), aimed.begin(), aimed.end());
  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    ExpectNoMismatches("garbage", CheckAllPresets("garbage", clean, rays, mode));
    for (const std::string& preset : CheckedPresets()) {
      absl::StatusOr<KdTree> tree = BuildKdTree(clean, *ConfigFor(preset));
      ASSERT_TRUE(tree.ok()) << tree.status();
      size_t nan_hits = 0, nan_pixels = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        const Hit h = Intersect(*tree, rays[i], WithTest(mode));
        if (!h.hit()) continue;
        nan_hits += !(std::isfinite(h.t) && std::isfinite(h.u) && std::isfinite(h.v));
        if (i < pixels) {
          const Vec3 n = GeometricNormal(clean.a(h.tri), clean.b(h.tri), clean.c(h.tri));
          const float shade = std::fabs(Dot(n, Normalize(rays[i].dir)));
          nan_pixels += !std::isfinite(shade);
        }
      }
      EXPECT_EQ(nan_hits, 0u) << preset;
      EXPECT_EQ(nan_pixels, 0u) << preset;
    }
  }
}

TEST(Garbage, KeptDegenerateTrianglesBuildAndAreReported) {
  const Dirty dirty = MakeDirty();
  TriangleSoup finite;  // only the non-finite triangles removed
  std::vector<bool> degenerate;
  for (size_t t = 0; t < dirty.soup.size(); ++t) {
    if (dirty.nonfinite.count(t)) continue;
    finite.Add(dirty.soup.a(t), dirty.soup.b(t), dirty.soup.c(t));
    degenerate.push_back(dirty.degenerate.count(t) > 0);
  }
  const std::vector<Ray> rays = AimedRays(dirty.aim);
  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    ExpectNoMismatches("garbage_kept", CheckAllPresets("garbage_kept", finite, rays, mode));
    absl::StatusOr<KdTree> tree = BuildKdTree(finite, Config());
    ASSERT_TRUE(tree.ok()) << tree.status();
    size_t degenerate_hits = 0, nan_hits = 0;
    for (const Ray& ray : rays) {
      const Hit h = Intersect(*tree, ray, WithTest(mode));
      if (!h.hit()) continue;
      degenerate_hits += degenerate[h.tri];
      nan_hits += !(std::isfinite(h.t) && std::isfinite(h.u) && std::isfinite(h.v));
    }
    EXPECT_EQ(nan_hits, 0u);
    if (mode == IntersectionMode::kWatertight) {
      EXPECT_EQ(degenerate_hits, 0u);
    }
    std::printf("ROBUST_JSON {\"case\": \"garbage/kept_degenerate\", \"mode\": \"%s\", "
                "\"aimed_rays\": %zu, \"degenerate_triangle_hits\": %zu}\n",
                IntersectionModeName(mode), rays.size(), degenerate_hits);
  }
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
