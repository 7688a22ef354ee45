#include "cc/render/manifest.h"

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "absl/strings/str_cat.h"
#include "cc/render/json.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

// A fresh checkout-like root (data/cache/scenes/) per suffix.
std::string TempRoot(const std::string& suffix = "") {
  const char* dir = std::getenv("TEST_TMPDIR");
  const std::string root = absl::StrCat(dir ? dir : "/tmp", "/manifest_test", suffix);
  mkdir(root.c_str(), 0755);
  mkdir((root + "/data").c_str(), 0755);
  mkdir((root + "/data/cache").c_str(), 0755);
  mkdir((root + "/data/cache/scenes").c_str(), 0755);
  return root;
}

void Write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// A root whose scene index holds one scene, "m", a triangle at ROOT/m.obj.
std::string OneSceneRoot(const std::string& suffix) {
  const std::string root = TempRoot(suffix);
  Write(root + "/m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Write(root + "/data/cache/scenes/index.json",
        absl::StrCat(R"({"scenes": {"m": {"file": ")", root, R"(/m.obj"}}})"));
  return root;
}

TEST(ViewFromManifest, CameraAndLight) {
  absl::StatusOr<nlohmann::json> e = ParseJson(
      R"({"name": "x", "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0],
          "up": [0, 1, 0], "fov_deg": 30}, "light": {"position": [1, 2, 3]}})",
      "m");
  ASSERT_TRUE(e.ok());
  absl::StatusOr<View> v = ViewFromManifestEntry(*e, "m: x");
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_EQ(v->camera.position, Vec3(0, 1, 5));
  EXPECT_EQ(v->camera.fov_deg, 30.0f);
  ASSERT_EQ(v->lights.size(), 1u);
  EXPECT_EQ(v->lights[0].position, Vec3(1, 2, 3));
  EXPECT_EQ(v->width, 800);
}

TEST(ViewFromManifest, NullLightMeansNoLights) {
  absl::StatusOr<nlohmann::json> e = ParseJson(
      R"({"camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]}, "light": null})", "m");
  ASSERT_TRUE(e.ok());
  absl::StatusOr<View> v = ViewFromManifestEntry(*e, "m");
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_TRUE(v->lights.empty());
}

TEST(ViewFromManifest, BadFieldsAreErrors) {
  for (const char* text : {R"({"light": null})",
                           R"({"camera": {"position": [0, 1], "look_at": [0, 0, 0]}})",
                           R"({"camera": {"position": [0, 1, 5], "look_at": "x"}})",
                           R"({"camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]}, "light": 3})",
                           R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 0]}})"}) {
    absl::StatusOr<nlohmann::json> e = ParseJson(text, "m");
    ASSERT_TRUE(e.ok()) << text;
    EXPECT_FALSE(ViewFromManifestEntry(*e, "m").ok()) << text;
  }
}

TEST(ResolveScene, IndexAndManifest) {
  const std::string root = TempRoot();
  Write(root + "/data/cache/scenes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Write(root + "/data/cache/scenes/index.json",
        R"({"scenes": {"tri": {"file": "data/cache/scenes/tri.obj", "triangles": 1},
                       "gone": {"file": "data/cache/scenes/gone.obj"}}})");
  Write(root + "/data/manifest.json",
        R"({"scenes": [{"name": "tri", "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0],
            "up": [0, 1, 0], "fov_deg": 45}, "light": null}]})");
  absl::StatusOr<SceneRef> ref = ResolveScene(root, "tri");
  ASSERT_TRUE(ref.ok()) << ref.status();
  EXPECT_EQ(ref->mesh_path, root + "/data/cache/scenes/tri.obj");
  EXPECT_TRUE(ref->has_view);
  EXPECT_EQ(ref->view.camera.position, Vec3(0, 0, 3));
  EXPECT_TRUE(ref->view.lights.empty());

  absl::StatusOr<SceneRef> missing = ResolveScene(root, "nope");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("data/fetch.py"), std::string::npos);
  EXPECT_FALSE(ResolveScene(root, "gone").ok());
}

TEST(ResolveScene, MalformedManifestNamesFileAndLine) {
  const std::string root = OneSceneRoot("3");
  Write(root + "/data/manifest.json", "{\"scenes\": [\n  {\"name\": \"m\",}\n]}\n");
  absl::StatusOr<SceneRef> ref = ResolveScene(root, "m");
  ASSERT_FALSE(ref.ok());
  EXPECT_NE(ref.status().message().find(root + "/data/manifest.json: line 2, column 16: "),
            std::string::npos)
      << ref.status();
}

TEST(ResolveScene, NoManifestLeavesNoView) {
  const std::string root = OneSceneRoot("2");
  absl::StatusOr<SceneRef> ref = ResolveScene(root, "m");
  ASSERT_TRUE(ref.ok()) << ref.status();
  EXPECT_FALSE(ref->has_view);
  EXPECT_EQ(ref->mesh_path, root + "/m.obj");
}

}  // namespace
}  // namespace kdtree
