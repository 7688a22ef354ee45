#include "cc/render/view.h"

#include <cstdlib>
#include <string>

#include "absl/strings/str_cat.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(ViewParser, ParsesFullFile) {
  absl::StatusOr<View> v = ParseView(
      "# bunny\ncamera {\n  position 0 0.1 2.5  look_at 0 0.1 0\n  up 0 1 0  fov 40\n}\n"
      "resolution 640 480\nlight{position 1 2 3}\nlight { position -1 2 3 } // second\n"
      "ambient_occlusion { samples 16 distance 0.25 }\n",
      "b.view");
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_EQ(v->camera.position, Vec3(0, 0.1f, 2.5f));
  EXPECT_EQ(v->camera.look_at, Vec3(0, 0.1f, 0));
  EXPECT_EQ(v->camera.fov_deg, 40.0f);
  EXPECT_EQ(v->width, 640);
  EXPECT_EQ(v->height, 480);
  ASSERT_EQ(v->lights.size(), 2u);
  EXPECT_EQ(v->lights[1].position, Vec3(-1, 2, 3));
  EXPECT_EQ(v->ao.samples, 16);
  EXPECT_EQ(v->ao.distance, 0.25f);
}

TEST(ViewParser, DefaultsWhenOptionalPartsAreAbsent) {
  absl::StatusOr<View> v = ParseView("camera { position 0 0 5 look_at 0 0 0 }", "d.view");
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_EQ(v->camera.up, Vec3(0, 1, 0));
  EXPECT_EQ(v->camera.fov_deg, 45.0f);
  EXPECT_EQ(v->width, 800);
  EXPECT_EQ(v->height, 800);
  EXPECT_TRUE(v->lights.empty());
  EXPECT_FALSE(v->ao.enabled());
}

TEST(ViewParser, MalformedFilesNameLineAndReason) {
  const std::string cam = "camera { position 0 0 5 look_at 0 0 0 }\n";
  const struct {
    std::string text;
    std::string expected;  // substring of the message, including "file:line"
  } cases[] = {
      {"", "v.view:1: no 'camera' block"},
      {"resolution 8 8\n", "v.view:2: no 'camera' block"},
      {cam + cam, "v.view:2: second 'camera' block"},
      {"camera { position 0 0 5 }", "v.view:1: camera has no 'look_at'"},
      {"camera {\n look_at 0 0 0 }", "v.view:1: camera has no 'position'"},
      {"camera {\n position 0 0 x look_at 0 0 0 }", "v.view:2: expected a number for camera position, got 'x'"},
      {"camera {\n position 0 0 5\n position 1 1 1 look_at 0 0 0 }", "v.view:3: 'position' given twice"},
      {"camera { position 0 0 5 look_at 0 0 0 zoom 2 }", "v.view:1: unknown camera key 'zoom'"},
      {"camera position 0 0 5", "v.view:1: expected '{' after 'camera'"},
      {"camera {\n position 0 0 5\n look_at 0 0 0\n", "v.view:1: unterminated 'camera' block"},
      {cam + "resolution 0 8", "v.view:2: resolution must be between 1 and 16384"},
      {cam + "resolution 8", "v.view:2: missing resolution height"},
      {cam + "resolution 8 8.5", "v.view:2: expected an integer for resolution height"},
      {cam + "\nlight { }", "v.view:3: light has no 'position'"},
      {cam + "light { position 1 2 3 colour 1 1 1 }", "v.view:2: unknown light key 'colour'"},
      {cam + "ambient_occlusion { samples 4 }", "v.view:2: ambient_occlusion needs 'samples' and 'distance'"},
      {cam + "ambient_occlusion { samples 0 distance 1 }", "v.view:2: ambient_occlusion samples must be at least 1"},
      {cam + "ambient_occlusion { samples 4 distance -1 }", "ambient_occlusion distance must be positive"},
      {cam + "fog { }", "v.view:2: unknown keyword 'fog'"},
      {"camera { position 0 0 5 look_at 0 0 5 }", "v.view: camera position equals look_at"},
      {"camera { position 0 0 5 look_at 0 0 0 up 0 0 1 }", "up is parallel"},
      {"camera { position 0 0 5 look_at 0 0 0 fov 180 }", "fov must be between 0 and 180"},
      {"camera { position 0 0 inf look_at 0 0 0 }", "v.view:1: camera position is not finite"},
  };
  for (const auto& c : cases) {
    absl::StatusOr<View> v = ParseView(c.text, "v.view");
    ASSERT_FALSE(v.ok()) << c.text;
    EXPECT_NE(v.status().message().find(c.expected), std::string::npos)
        << "input:\n" << c.text << "\nmessage: " << v.status().message();
  }
}

TEST(ViewParser, NoMoreLightsThanARayRecordCanNumber) {
  std::string text = "camera { position 0 0 5 look_at 0 0 0 }\n";
  for (size_t i = 0; i < kMaxLights; ++i) text += "light { position 1 2 3 }\n";
  EXPECT_TRUE(ParseView(text, "v.view").ok());
  text += "light { position 1 2 3 }\n";
  absl::StatusOr<View> v = ParseView(text, "v.view");
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.status().message().find("at most 65535 lights"), std::string::npos) << v.status();
}

TEST(CheckSceneScale, RefusesScenesFloatsCannotTrace) {
  const auto box = [](float lo, float hi) { return AABB{Vec3(lo, lo, lo), Vec3(hi, hi, hi)}; };
  EXPECT_TRUE(CheckSceneScale(box(-1, 1)).ok());
  EXPECT_TRUE(CheckSceneScale(box(1.5e5f - 10, 1.5e5f + 10)).ok());  // the offset sphere
  const absl::Status tiny = CheckSceneScale(box(0, 1e-30f));
  EXPECT_NE(tiny.message().find("would underflow"), std::string::npos) << tiny;
  const absl::Status huge = CheckSceneScale(box(-1e30f, 1e30f));
  EXPECT_NE(huge.message().find("would overflow"), std::string::npos) << huge;
  const absl::Status far = CheckSceneScale(box(1e20f, 1e20f + 1e13f));
  EXPECT_NE(far.message().find("too few bits"), std::string::npos) << far;
  EXPECT_FALSE(CheckSceneScale(AABB()).ok());
}

TEST(ViewParser, TextRoundTrip) {
  View v;
  v.camera.position = Vec3(0.1f, 0.2f, 0.3f);
  v.camera.look_at = Vec3(-1.0f / 3.0f, 2.0f, 1e-7f);
  v.camera.fov_deg = 33.3f;
  v.width = 17;
  v.height = 9;
  v.lights.push_back(PointLight{Vec3(1, 2, 3)});
  v.ao.samples = 8;
  v.ao.distance = 0.1f;
  absl::StatusOr<View> back = ParseView(ViewToText(v), "rt");
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->camera.position, v.camera.position);
  EXPECT_EQ(back->camera.look_at, v.camera.look_at);
  EXPECT_EQ(back->camera.fov_deg, v.camera.fov_deg);
  EXPECT_EQ(back->width, 17);
  EXPECT_EQ(back->lights[0].position, v.lights[0].position);
  EXPECT_EQ(back->ao.distance, v.ao.distance);
}

TEST(ViewParser, MissingFileIsNotFound) {
  absl::StatusOr<View> v = LoadViewFile("/nonexistent/x.view");
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.status().message().find("/nonexistent/x.view"), std::string::npos);
}

// Issue 24: a directory given as the view file is refused by name (it was
// read as an empty file: "no 'camera' block").
TEST(ViewParser, ADirectoryIsRefusedByName) {
  const char* dir = std::getenv("TEST_TMPDIR");
  ASSERT_NE(dir, nullptr);
  absl::StatusOr<View> v = LoadViewFile(dir);
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.status().message(), std::string(dir) + ": the view file is a directory");
}

}  // namespace
}  // namespace kdtree
