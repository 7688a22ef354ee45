#include "cc/kdtree/clipping.h"

#include "gtest/gtest.h"

namespace kdtree {
namespace {

const AABB kHuge({-100, -100, -100}, {100, 100, 100});

void ExpectBox(const AABB& b, Vec3 lo, Vec3 hi) {
  EXPECT_FLOAT_EQ(b.lo.x, lo.x);
  EXPECT_FLOAT_EQ(b.lo.y, lo.y);
  EXPECT_FLOAT_EQ(b.lo.z, lo.z);
  EXPECT_FLOAT_EQ(b.hi.x, hi.x);
  EXPECT_FLOAT_EQ(b.hi.y, hi.y);
  EXPECT_FLOAT_EQ(b.hi.z, hi.z);
}

TEST(Clipping, TouchingTrianglesAreNotClipped) {
  // (-1, -1, 0) and (0, 1, 1): one vertex on the plane, the rest on one side.
  EXPECT_EQ(ClassifyTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0, 1.0f), ClipCase::kNotStraddling);
  EXPECT_EQ(ClassifyTriangle({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, 0, 1.0f), ClipCase::kNotStraddling);
  AABB l, r;
  EXPECT_EQ(ClipTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0, 1.0f, kHuge, true, &l, &r),
            ClipCase::kNotStraddling);
}

TEST(Clipping, MiddleVertexOnThePlane) {  // (-1, 0, 1)
  for (bool conservative : {false, true}) {
    AABB l, r;
    ASSERT_EQ(ClipTriangle({0, 0, 0}, {1, 1, 0}, {2, 0, 0}, 0, 1.0f, kHuge, conservative, &l, &r),
              ClipCase::kMiddleOnPlane);
    ExpectBox(l, {0, 0, 0}, {1, 1, 0});
    ExpectBox(r, {1, 0, 0}, {2, 1, 0});
  }
}

TEST(Clipping, LowVertexAlone) {  // (-1, 1, 1)
  for (bool conservative : {false, true}) {
    AABB l, r;
    ASSERT_EQ(ClipTriangle({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, 0, 1.0f, kHuge, conservative, &l, &r),
              ClipCase::kLowAlone);
    ExpectBox(l, {0, 0, 0}, {1, 1, 0});
    ExpectBox(r, {1, 0, 0}, {2, 2, 0});
  }
}

TEST(Clipping, HighVertexAlone) {  // (-1, -1, 1)
  for (bool conservative : {false, true}) {
    AABB l, r;
    ASSERT_EQ(ClipTriangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0, 1.0f, kHuge, conservative, &l, &r),
              ClipCase::kHighAlone);
    ExpectBox(l, {0, 0, 0}, {1, 2, 0});
    ExpectBox(r, {1, 0, 0}, {2, 1, 0});
  }
}

TEST(Clipping, ResultIsIntersectedWithTheReferenceBox) {
  AABB l, r;
  const AABB ref({0, 0.5f, 0}, {2, 2, 0});  // already clipped at y = 0.5 earlier
  ASSERT_EQ(ClipTriangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0, 1.0f, ref, false, &l, &r),
            ClipCase::kHighAlone);
  ExpectBox(l, {0, 0.5f, 0}, {1, 2, 0});
  ExpectBox(r, {1, 0.5f, 0}, {2, 1, 0});
}

TEST(Clipping, ConservativeBoxesContainTheExactCutPoints) {
  // Cut points at non-representable coordinates: the outward-rounded boxes
  // must contain the double-precision cut points.
  const Vec3 a(0.1f, 0.3f, 0.7f), b(2.9f, 1.3f, -0.2f), c(0.4f, 2.2f, 0.33f);
  const float pos = 1.7f;
  AABB l, r;
  ASSERT_NE(ClipTriangle(a, b, c, 0, pos, kHuge, true, &l, &r), ClipCase::kNotStraddling);
  for (const Vec3* p : {&a, &c}) {  // the edges to b cross the plane
    const double t = (double(pos) - p->x) / (double(b.x) - p->x);
    const double y = p->y + (double(b.y) - p->y) * t, z = p->z + (double(b.z) - p->z) * t;
    EXPECT_LE(double(l.lo.y), y);
    EXPECT_GE(double(l.hi.y), y);
    EXPECT_LE(double(l.lo.z), z);
    EXPECT_GE(double(l.hi.z), z);
    EXPECT_LE(double(r.lo.y), y);
    EXPECT_GE(double(r.hi.y), y);
  }
  EXPECT_EQ(l.hi.x, pos);
  EXPECT_EQ(r.lo.x, pos);
}

}  // namespace
}  // namespace kdtree
