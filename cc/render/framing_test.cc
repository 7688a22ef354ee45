#include "cc/render/framing.h"

#include <cmath>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(AutoView, FramesTheBoxFromAboveFront) {
  const AABB box(Vec3(-1, 0, -2), Vec3(3, 2, 2));
  const View v = AutoView(box);
  ASSERT_TRUE(v.Validate("auto").ok());
  EXPECT_EQ(v.camera.look_at, Vec3(1, 1, 0));
  EXPECT_GT(v.camera.position.z, box.hi.z);      // +z side, outside the box
  EXPECT_GT(v.camera.position.y, 1.0f);          // slightly above the centre
  EXPECT_NEAR(v.camera.position.x, 1.0f, 1e-5f);
  EXPECT_EQ(v.camera.fov_deg, 45.0f);
  ASSERT_EQ(v.lights.size(), 1u);
  EXPECT_GT(v.lights[0].position.y, box.hi.y);   // above
  EXPECT_GT(v.lights[0].position.z, 0.0f);       // in front
  // The bounding sphere fits the view: its angular radius is below 22.5 deg.
  const float r = Length(box.hi - box.lo) * 0.5f;
  const float d = Length(v.camera.position - v.camera.look_at);
  EXPECT_LT(r / d, std::sin(22.5f * 3.14159265f / 180.0f));
}

// The manifest's first scene (data/manifest.json): bounds, camera and light
// as stored there, which fetch.py's Python rule once computed.
TEST(FrameBounds, GivesTheManifestsCamera) {
  const FramedView v = FrameBounds({-1.0, -0.991233, -0.775047}, {1.0, 0.991233, 0.775047},
                                   Framing{1, false});
  EXPECT_EQ(v.position, (Point3d{0.0, 1.14137, 4.25967}));
  EXPECT_EQ(v.look_at, (Point3d{0.0, 0.0, 0.0}));
  EXPECT_EQ(v.up, (Point3d{0.0, 1.0, 0.0}));
  EXPECT_EQ(v.fov_deg, 45.0);
  EXPECT_EQ(v.light, (Point3d{0.803623, 2.41087, 1.60725}));
}

TEST(FrameBounds, ZUpLandscapesAreSeenFromMinusYAndHigher) {
  const FramedView object = FrameBounds({0, 0, 0}, {10, 10, 1}, Framing{2, false});
  const FramedView land = FrameBounds({0, 0, 0}, {10, 10, 1}, Framing{2, true});
  EXPECT_EQ(land.up, (Point3d{0.0, 0.0, 1.0}));
  EXPECT_LT(land.position[1], 0.0);  // front is -y
  EXPECT_GT(land.position[2], object.position[2]);
  EXPECT_EQ(land.position[0], 5.0);
}

TEST(ParseFraming, NamesWhatItRefuses) {
  EXPECT_TRUE(ParseFraming(1, "object").ok());
  EXPECT_TRUE(ParseFraming(2, "interior")->raised_35);
  EXPECT_FALSE(ParseFraming(1, "object")->raised_35);
  EXPECT_FALSE(ParseFraming(3, "object").ok());
  absl::StatusOr<Framing> bad = ParseFraming(1, "portrait");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("portrait"), std::string::npos);
}

}  // namespace
}  // namespace kdtree
