#include "cc/kdtree/perfect_split.h"

#include <random>

#include "cc/kdtree/clipping.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

bool Inside(const Vec3& p, const AABB& b) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
         p.z <= b.hi.z;
}

TEST(PerfectSplit, BoxHoldsEveryPointOfTheTriangleInsideAndNoMore) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 2.0f), w(0.0f, 1.0f);
  int clipped = 0, tighter = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const AABB box({0, 0, 0}, {1, 1, 1});
    AABB got;
    const bool hit = ClipTriangleToBox(a, b, c, box, &got);
    // Sample the triangle; every sample inside the box lies in `got`.
    int inside = 0;
    for (int s = 0; s < 400; ++s) {
      float b1 = w(rng), b2 = w(rng);
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      const Vec3 p = a + (b - a) * b1 + (c - a) * b2;
      if (!Inside(p, box)) continue;
      ++inside;
      ASSERT_TRUE(hit) << trial;
      EXPECT_TRUE(Inside(p, got)) << trial;
    }
    if (!hit) continue;
    ++clipped;
    EXPECT_TRUE(got.Valid());
    EXPECT_TRUE(Inside(got.lo, box) && Inside(got.hi, box));
    // Never looser than the report's box clipping at one plane (x = 1) then
    // intersected with the box.
    AABB left, right;
    AABB tri;
    tri.Extend(a), tri.Extend(b), tri.Extend(c);
    if (ClipTriangle(a, b, c, 0, 1.0f, tri, true, &left, &right) != ClipCase::kNotStraddling) {
      const AABB report = Intersect(left, box);
      if (report.Valid()) {
        for (int k = 0; k < 3; ++k) {
          // (up to the conservative 1e-6 padding of perfect_split.h)
          EXPECT_GE(got.lo[k], report.lo[k] - 1e-5f) << trial;
          EXPECT_LE(got.hi[k], report.hi[k] + 1e-5f) << trial;
        }
        tighter += got.SurfaceArea() < report.SurfaceArea();
      }
    }
  }
  EXPECT_GT(clipped, 200);
  EXPECT_GT(tighter, 10) << "perfect splits should often be strictly tighter";
}

TEST(PerfectSplit, MissAndTouch) {
  const AABB box({0, 0, 0}, {1, 1, 1});
  AABB got;
  // Entirely beside the box.
  EXPECT_FALSE(ClipTriangleToBox({2, 0, 0}, {3, 0, 0}, {2, 1, 0}, box, &got));
  // Its box overlaps the box's corner region, the triangle does not.
  EXPECT_FALSE(ClipTriangleToBox({1.5f, -0.6f, 0.5f}, {-0.6f, 1.5f, 0.5f}, {2, 2, 0.5f},
                                 AABB({0, 0, 0}, {0.4f, 0.4f, 1}), &got));
  // Touching the face x = 1 counts (conservative).
  ASSERT_TRUE(ClipTriangleToBox({1, 0.2f, 0.2f}, {2, 0.2f, 0.8f}, {2, 0.8f, 0.2f}, box, &got));
  EXPECT_EQ(got.lo.x, 1.0f);
  EXPECT_EQ(got.hi.x, 1.0f);
  // A triangle lying in the face z = 0.
  ASSERT_TRUE(ClipTriangleToBox({-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}, box, &got));
  EXPECT_EQ(got.lo.z, 0.0f);
  EXPECT_EQ(got.hi.x, 1.0f);
}

}  // namespace
}  // namespace kdtree
