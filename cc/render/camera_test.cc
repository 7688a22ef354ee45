#include "cc/render/camera.h"

#include <cmath>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Camera, CentrePixelRayPointsAtLookAt) {
  CameraSpec spec;
  spec.position = Vec3(1, 2, 5);
  spec.look_at = Vec3(0.5f, 0.25f, -1);
  spec.fov_deg = 45;
  const Camera cam(spec, 101, 101);  // odd: pixel 50 is the centre
  const Ray r = cam.PrimaryRay(50, 50);
  const Vec3 want = Normalize(spec.look_at - spec.position);
  EXPECT_EQ(r.origin, spec.position);
  EXPECT_NEAR(r.dir.x, want.x, 1e-6f);
  EXPECT_NEAR(r.dir.y, want.y, 1e-6f);
  EXPECT_NEAR(r.dir.z, want.z, 1e-6f);
  EXPECT_NEAR(Length(r.dir), 1.0f, 1e-6f);
  EXPECT_EQ(r.tmin, 0.0f);
  EXPECT_TRUE(std::isinf(r.tmax));
}

TEST(Camera, FieldOfViewAndOrientation) {
  CameraSpec spec;
  spec.position = Vec3(0, 0, 0);
  spec.look_at = Vec3(0, 0, -1);
  spec.fov_deg = 90;
  const int n = 1000;
  const Camera cam(spec, n, n);
  // Top row looks up, left column looks left; the edge pixel centres are half a
  // pixel inside the 45 degree half-angle.
  const Ray top = cam.PrimaryRay(n / 2, 0);
  const Ray left = cam.PrimaryRay(0, n / 2);
  EXPECT_GT(top.dir.y, 0.0f);
  EXPECT_LT(left.dir.x, 0.0f);
  const float half = std::atan2(top.dir.y, -top.dir.z) * 180.0f / 3.14159265f;
  EXPECT_NEAR(half, 45.0f, 0.1f);
  EXPECT_LT(half, 45.0f);
}

TEST(Camera, WideImageWidensHorizontally) {
  CameraSpec spec;
  spec.position = Vec3(0, 0, 0);
  spec.look_at = Vec3(0, 0, -1);
  spec.fov_deg = 60;
  const Camera cam(spec, 400, 200);
  const Ray right = cam.PrimaryRay(399, 100);
  const Ray top = cam.PrimaryRay(200, 0);
  EXPECT_NEAR(right.dir.x / -right.dir.z, 2.0f * top.dir.y / -top.dir.z, 0.02f);
}

}  // namespace
}  // namespace kdtree
