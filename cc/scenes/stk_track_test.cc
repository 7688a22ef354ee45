#include "cc/scenes/stk_track.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/spm_testing.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

namespace fs = std::filesystem;

// One triangle with corners at the origin, +x and +y.
Mesh Corner() {
  Mesh m;
  m.AddVertex({0, 0, 0});
  m.AddVertex({1, 0, 0});
  m.AddVertex({0, 1, 0});
  m.AddTriangle(0, 1, 2);
  return m;
}

// `n` triangles, all equal to Corner() (to tell models apart by count).
Mesh Corners(int n) {
  Mesh m;
  for (int i = 0; i < n; ++i) m.Append(Corner());
  return m;
}

// A fresh data directory: data/tracks/t/, data/library/, data/models/.
class StkTrackTest : public testing::Test {
 protected:
  void SetUp() override {
    const char* tmp = std::getenv("TEST_TMPDIR");
    data_ = fs::path(tmp != nullptr ? tmp : "/tmp") /
            testing::UnitTest::GetInstance()->current_test_info()->name() / "data";
    fs::remove_all(data_);
    track_ = (data_ / "tracks" / "t").string();
    Write("tracks/t/track.spm", EncodeSpm(Corners(1)));
    Write("tracks/t/two.spm", EncodeSpm(Corners(2)));
    Write("tracks/t/three.spm", EncodeSpm(Corners(3)));
    Write("models/shared.spm", EncodeSpm(Corners(5)));
  }

  void Write(const std::string& relative, const std::string& bytes) {
    const fs::path path = data_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
  }

  // scene.xml with the main mesh and `body` (elements of <scene>).
  void Scene(const std::string& body) {
    Write("tracks/t/scene.xml",
          absl::StrCat("<?xml version=\"1.0\"?>\n<scene>\n  <track model=\"track.spm\" x=\"0\" "
                       "y=\"0\" z=\"0\">\n  </track>\n",
                       body, "</scene>\n"));
  }

  absl::StatusOr<Mesh> Read(StkTrackOptions options = {}) {
    stats_ = StkTrackStats();
    return ReadStkTrack(track_, options, &stats_);
  }

  static StkTrackOptions LeftHanded() {
    StkTrackOptions o;
    o.right_handed = false;
    return o;
  }

  fs::path data_;
  std::string track_;
  StkTrackStats stats_;
};

void ExpectNear(const Vec3& got, const Vec3& want) {
  EXPECT_NEAR(got.x, want.x, 1e-5) << "y " << got.y << " z " << got.z;
  EXPECT_NEAR(got.y, want.y, 1e-5) << "x " << got.x << " z " << got.z;
  EXPECT_NEAR(got.z, want.z, 1e-5) << "x " << got.x << " y " << got.y;
}

TEST_F(StkTrackTest, MainMeshAlone) {
  Scene("");
  absl::StatusOr<Mesh> m = Read(LeftHanded());
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->TriangleCount(), 1u);
  EXPECT_EQ(stats_.placed, 1);
  EXPECT_EQ(stats_.models, 1);
}

TEST_F(StkTrackTest, TransformIsTranslateRotateZYXScale) {
  // Corner (0,0,0) (1,0,0) (0,1,0), scaled by (2,3,4), rotated: x by 90 turns
  // +y into +z; then y by 90 turns +z into +x; then moved by (10,20,30).
  Scene("  <object type=\"animation\" model=\"track.spm\" xyz=\"10 20 30\" hpr=\"90 90 0\" "
        "scale=\"2 3 4\"/>\n");
  absl::StatusOr<Mesh> m = Read(LeftHanded());
  ASSERT_TRUE(m.ok()) << m.status();
  ASSERT_EQ(m->vertices.size(), 6u);
  ExpectNear(m->vertices[3], {10, 20, 30});
  ExpectNear(m->vertices[4], {10, 20, 28});  // +x * 2: y(90) takes +x to -z
  ExpectNear(m->vertices[5], {13, 20, 30});  // +y * 3: x(90) to +z, y(90) to +x
}

TEST_F(StkTrackTest, ZRotationAndRightHandedFrame) {
  Scene("  <static-object model=\"track.spm\" xyz=\"1 2 3\" hpr=\"0 0 90\"/>\n");
  absl::StatusOr<Mesh> m = Read();  // right-handed: z negated at the end
  ASSERT_TRUE(m.ok()) << m.status();
  ExpectNear(m->vertices[4], {1, 3, -3});  // +x turned to +y
  ExpectNear(m->vertices[5], {0, 2, -3});  // +y turned to -x
  ExpectNear(m->vertices[1], {1, 0, 0});
}

TEST_F(StkTrackTest, LodInstanceTakesTheNearestLevelAtTheInstanceTransform) {
  Scene(
      "  <lod>\n"
      "   <group name=\"g\">\n"
      "    <static-object lod_distance=\"100\" lod_group=\"g\" model=\"two.spm\" xyz=\"50 0 0\"/>\n"
      "    <static-object lod_distance=\"20\" lod_group=\"g\" model=\"shared.spm\" "
      "interaction=\"physics-only\"/>\n"
      "    <static-object lod_distance=\"40\" lod_group=\"g\" model=\"three.spm\" xyz=\"60 0 0\"/>\n"
      "   </group>\n"
      "  </lod>\n"
      "  <object type=\"animation\" lod_instance=\"true\" lod_group=\"g\" xyz=\"0 5 0\"/>\n");
  absl::StatusOr<Mesh> m = Read(LeftHanded());
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->TriangleCount(), 1u + 3u);  // three.spm: distance 40 (20 is collision-only)
  EXPECT_EQ(stats_.lod_instances, 1);
  ExpectNear(m->vertices.back(), {0, 6, 0});  // the instance's xyz, not the member's
}

TEST_F(StkTrackTest, LibrariesNestAndUseTheirOwnLodGroups) {
  Write("library/inner/node.xml",
        "<scene>\n"
        "  <lod><group name=\"leaf\"><static-object lod_distance=\"1\" model=\"leaf.spm\"/>"
        "</group></lod>\n"
        "  <object lod_instance=\"true\" lod_group=\"leaf\" xyz=\"0 0 1\"/>\n"
        "  <object model=\"shared.spm\" interaction=\"physicsonly\"/>\n"
        "</scene>\n");
  Write("library/inner/leaf.spm", EncodeSpm(Corners(7)));
  Write("library/outer/node.xml",
        "<scene>\n"
        "  <library name=\"inner\" xyz=\"0 1 0\" scale=\"2 2 2\"/>\n"
        "  <object model=\"two.spm\"/>\n"  // found in the track directory
        "</scene>\n");
  Scene("  <library name=\"outer\" xyz=\"100 0 0\" hpr=\"0 0 0\"/>\n"
        "  <library name=\"outer\" xyz=\"200 0 0\"/>\n");
  absl::StatusOr<Mesh> m = Read(LeftHanded());
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->TriangleCount(), 1u + 2 * (7u + 2u));
  EXPECT_EQ(stats_.libraries, 4);
  EXPECT_EQ(stats_.skipped["interaction=physicsonly"], 2);
  // First leaf: outer (100,0,0) + inner (0,1,0) + 2 * (0,0,1).
  ExpectNear(m->vertices[3], {100, 1, 2});
}

TEST_F(StkTrackTest, ConditionsFollowTheRaceDirection) {
  Scene("  <object model=\"two.spm\" if=\"isTrackReverse\"/>\n"
        "  <object model=\"three.spm\" if=\"isTrackNotReverse\"/>\n"
        "  <object model=\"shared.spm\" if=\"false\"/>\n"
        "  <object model=\"track.spm\" if=\"someScriptFunction\"/>\n");
  absl::StatusOr<Mesh> forward = Read();
  ASSERT_TRUE(forward.ok()) << forward.status();
  EXPECT_EQ(forward->TriangleCount(), 1u + 3u + 1u);
  EXPECT_EQ(stats_.skipped["if=isTrackReverse"], 1);
  EXPECT_EQ(stats_.skipped["if=false"], 1);
  StkTrackOptions reverse;
  reverse.reverse = true;
  EXPECT_EQ(Read(reverse)->TriangleCount(), 1u + 2u + 1u);
  StkTrackOptions all;
  all.evaluate_conditions = false;
  EXPECT_EQ(Read(all)->TriangleCount(), 1u + 2u + 3u + 5u + 1u);
}

TEST_F(StkTrackTest, ObjectsWithoutMeshesAreCountedNotPlaced) {
  Scene("  <object type=\"billboard\" texture=\"moon.png\" xyz=\"1 1 1\"/>\n"
        "  <object type=\"cutscene_camera\" model=\"two.spm\"/>\n"
        "  <object type=\"sfx-emitter\" sound=\"x.ogg\"/>\n"
        "  <light xyz=\"0 0 0\"/>\n  <particle-emitter kind=\"smoke\"/>\n");
  absl::StatusOr<Mesh> m = Read();
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->TriangleCount(), 1u);
  EXPECT_EQ(stats_.skipped["no mesh: object type=billboard"], 1);
  EXPECT_EQ(stats_.skipped["type=cutscene_camera"], 1);
  EXPECT_EQ(stats_.skipped["no mesh: object type=sfx-emitter"], 1);
}

TEST_F(StkTrackTest, ErrorsNameTheFileAndLine) {
  const std::string scene = track_ + "/scene.xml";
  struct Case {
    std::string body;
    std::string error;
  } cases[] = {
      {"  <object model=\"none.spm\"/>\n", scene + ":5: model 'none.spm' not found"},
      {"  <object lod_instance=\"true\" lod_group=\"nope\"/>\n",
       scene + ":5: unknown LOD group 'nope'"},
      {"  <object model=\"two.spm\" xyz=\"1 2\"/>\n", scene + ":5: xyz=\"1 2\": not three"},
      {"  <object model=\"two.spm\" hpr=\"1 2 nan\"/>\n", "not three numbers"},
      {"  <library name=\"missing\"/>\n", "library 'missing': " + data_.string()},
      {"  <object model=\"bad.spm\"/>\n", "bad.spm: not an .spm file"},
      {"  <object model=\"two.spm\">\n", scene + ": line 6: Start-end tags mismatch"},
      {"  <track model=\"two.spm\"/>\n", scene + ":5: a second <track> element"},
  };
  Write("tracks/t/bad.spm", "not an spm");
  for (const Case& c : cases) {
    Scene(c.body);
    absl::StatusOr<Mesh> m = Read();
    ASSERT_FALSE(m.ok()) << c.body;
    EXPECT_TRUE(absl::StrContains(m.status().message(), c.error)) << m.status();
  }
}

TEST_F(StkTrackTest, MissingSceneOrMainMeshIsAnError) {
  EXPECT_TRUE(absl::StrContains(Read().status().message(), "scene.xml: cannot open"));
  Write("tracks/t/scene.xml", "<scene><object model=\"two.spm\"/></scene>");
  EXPECT_TRUE(absl::StrContains(Read().status().message(), "no <track model=...> element"));
}

TEST_F(StkTrackTest, ALibraryIncludingItselfIsStopped) {
  Write("library/loop/node.xml", "<scene><library name=\"loop\"/></scene>");
  Scene("  <library name=\"loop\"/>\n");
  absl::StatusOr<Mesh> m = Read();
  ASSERT_FALSE(m.ok());
  EXPECT_TRUE(absl::StrContains(m.status().message(), "nested deeper than 8")) << m.status();
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
