#include "cc/scenes/assimp_mesh.h"

#include <cstdlib>
#include <fstream>
#include <string>

#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

std::string TempPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The writer's files come back with the same triangles, and once numbered by
// first use (as mesh_info --ply_out writes the parts) byte for byte.
TEST(ReadMesh, ReadsTheWritersPlyBack) {
  Mesh cube;
  AddBox(cube, {0.1f, 0, 0}, {1, 2.5f, 3});
  const std::string path = TempPath("cube.ply");
  ASSERT_TRUE(WritePly(path, cube).ok());
  absl::StatusOr<Mesh> back = ReadMesh(path);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->ToSoup().v, cube.ToSoup().v);
  const std::string again = TempPath("cube_again.ply");
  ASSERT_TRUE(WritePly(again, *back).ok());
  absl::StatusOr<Mesh> twice = ReadMesh(again);
  ASSERT_TRUE(twice.ok()) << twice.status();
  EXPECT_EQ(EncodePly(*twice), EncodePly(*back));
}

// OBJ polygons are triangulated; unused vertices are dropped and the rest
// numbered by first use.
TEST(ReadMesh, TriangulatesObjAndNumbersVerticesByFirstUse) {
  const std::string path = TempPath("quad.obj");
  WriteText(path, "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 2 3 4 5\n");
  absl::StatusOr<Mesh> m = ReadMesh(path);
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->TriangleCount(), 2u);
  ASSERT_EQ(m->vertices.size(), 4u);
  EXPECT_EQ(m->vertices[0], Vec3(0, 0, 0));
}

// Two triangles sharing an edge: PLY keeps the shared vertices, assimp's OBJ
// reader does not (assimp_mesh.h: subdivide and refine want PLY).
TEST(ReadMesh, PlyKeepsSharedVerticesObjDoesNot) {
  Mesh quad;
  quad.AddVertex({0, 0, 0});
  quad.AddVertex({1, 0, 0});
  quad.AddVertex({1, 1, 0});
  quad.AddVertex({0, 1, 0});
  quad.AddQuad(0, 1, 2, 3);
  const std::string ply = TempPath("quad.ply");
  ASSERT_TRUE(WritePly(ply, quad).ok());
  absl::StatusOr<Mesh> from_ply = ReadMesh(ply);
  ASSERT_TRUE(from_ply.ok()) << from_ply.status();
  EXPECT_EQ(from_ply->vertices.size(), 4u);
  const std::string obj = TempPath("two.obj");
  WriteText(obj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  absl::StatusOr<Mesh> from_obj = ReadMesh(obj);
  ASSERT_TRUE(from_obj.ok()) << from_obj.status();
  EXPECT_EQ(from_obj->TriangleCount(), 2u);
  EXPECT_EQ(from_obj->vertices.size(), 6u);
}

TEST(ReadMesh, ErrorsNameTheFile) {
  const std::string missing = TempPath("missing.ply");
  absl::StatusOr<Mesh> m = ReadMesh(missing);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find(missing), std::string::npos);
  const std::string dir = TempPath("");
  EXPECT_FALSE(ReadMesh(dir).ok());  // a directory is not a mesh
  const std::string junk = TempPath("junk.ply");
  WriteText(junk, "not a ply file\n");
  m = ReadMesh(junk);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find(junk), std::string::npos);
  const std::string lines = TempPath("lines.obj");
  WriteText(lines, "v 0 0 0\nv 1 0 0\nl 1 2\n");
  EXPECT_FALSE(ReadMesh(lines).ok());  // no triangles
}

TEST(ReadFlattened, CountsWithoutAMesh) {
  const std::string path = TempPath("tri.obj");
  WriteText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  FlattenTotals t;
  ASSERT_TRUE(ReadFlattened(path, {}, &t, nullptr).ok());
  EXPECT_EQ(t.triangles, 1u);
  EXPECT_EQ(t.triangles_unique, 1u);
  EXPECT_EQ(t.hi[0], 1.0);
  EXPECT_EQ(t.lo[1], 0.0);
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
