#include "cc/scenes/ply.h"

#include <cstdio>
#include <string>

#include "cc/scenes/mesh.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

Mesh UnitCube() {
  Mesh m;
  AddBox(m, {0, 0, 0}, {1, 2, 3});
  return m;
}

TEST(Ply, HeaderAndSizeAreExact) {
  const std::string bytes = EncodePly(UnitCube());
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment kdtree_repro cc/scenes generator\n"
      "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.size(), header.size() + 8 * 12 + 12 * 13);
  // Little-endian float 1.0f = 00 00 80 3f: vertex 1 is (1, 0, 0).
  EXPECT_EQ(bytes.substr(header.size() + 12, 4), std::string("\x00\x00\x80\x3f", 4));
}

TEST(Ply, BinaryRoundTripIsExact) {
  const Mesh cube = UnitCube();
  absl::StatusOr<Mesh> back = ParsePly(EncodePly(cube));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->vertices, cube.vertices);
  EXPECT_EQ(back->faces, cube.faces);
}

TEST(Ply, AsciiPolygonsAreFanTriangulatedAndOtherElementsSkipped) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 1\n"
      "property list uchar int vertex_indices\nelement edge 1\nproperty int a\nproperty int b\n"
      "end_header\n0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n0 1\n";
  absl::StatusOr<Mesh> m = ParsePly(text);
  ASSERT_TRUE(m.ok()) << m.status();
  ASSERT_EQ(m->vertices.size(), 4u);
  EXPECT_EQ(m->vertices[2], Vec3(1, 1, 0));
  ASSERT_EQ(m->faces.size(), 2u);
  EXPECT_EQ(m->faces[1], (Mesh::Face{0, 2, 3}));
}

TEST(Ply, RejectsBadInput) {
  EXPECT_FALSE(ParsePly("not a ply").ok());
  EXPECT_FALSE(ParsePly("ply\nformat binary_big_endian 1.0\nend_header\n").ok());
  EXPECT_FALSE(ParsePly("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                        "end_header\n")
                   .ok());  // truncated
  EXPECT_FALSE(ParsePly("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0\n3 0 1 2\n")
                   .ok());  // index out of range
}

TEST(Obj, ReadsVerticesFacesAndNegativeIndices) {
  absl::StatusOr<Mesh> m = ParseObj(
      "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n"
      "f -4 -3 -2\n");
  ASSERT_TRUE(m.ok()) << m.status();
  ASSERT_EQ(m->faces.size(), 3u);
  EXPECT_EQ(m->faces[1], (Mesh::Face{0, 2, 3}));
  EXPECT_EQ(m->faces[2], (Mesh::Face{0, 1, 2}));
  EXPECT_FALSE(ParseObj("v 0 0 0\nf 1 2 3\n").ok());
}

TEST(Ply, WriteThenReadMeshFromDisk) {
  const char* dir = std::getenv("TEST_TMPDIR");
  const std::string path = std::string(dir ? dir : "/tmp") + "/cube.ply";
  ASSERT_TRUE(WritePly(path, UnitCube()).ok());
  absl::StatusOr<Mesh> m = ReadMesh(path);
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->faces.size(), 12u);
  EXPECT_FALSE(ReadMesh(path + ".missing").ok());
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
