#include "cc/scenes/q3_bsp.h"

#include <cstring>
#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

// Builds a small IBSP 46 file: lumps 1 (textures), 10 (vertices),
// 11 (mesh vertices) and 13 (faces); the other lumps are empty.
class BspBuilder {
 public:
  int Texture(int flags) {
    std::string t(72, '\0');
    std::memcpy(&t[64], &flags, 4);
    textures_ += t;
    return static_cast<int>(textures_.size() / 72 - 1);
  }
  int Vertex(float x, float y, float z) {
    std::string v(44, '\0');
    const float p[3] = {x, y, z};
    std::memcpy(&v[0], p, 12);
    vertices_ += v;
    return static_cast<int>(vertices_.size() / 44 - 1);
  }
  void Face(int texture, int type, int vertex, int n_vertices, const std::vector<int>& meshverts,
            int w = 0, int h = 0) {
    const int first = static_cast<int>(meshverts_.size() / 4);
    for (int m : meshverts) meshverts_.append(reinterpret_cast<const char*>(&m), 4);
    std::string f(104, '\0');
    const int ints[7] = {texture, -1, type, vertex, n_vertices, first,
                         static_cast<int>(meshverts.size())};
    std::memcpy(&f[0], ints, sizeof(ints));
    std::memcpy(&f[96], &w, 4);
    std::memcpy(&f[100], &h, 4);
    faces_ += f;
  }
  std::string Build() const {
    std::string out = "IBSP";
    const int version = 46;
    out.append(reinterpret_cast<const char*>(&version), 4);
    std::string body;
    const int header = 8 + 17 * 8;
    std::string dir;
    for (int i = 0; i < 17; ++i) {
      const std::string* data = i == 1 ? &textures_ : i == 10 ? &vertices_
                                : i == 11 ? &meshverts_ : i == 13 ? &faces_ : nullptr;
      const int offset = header + static_cast<int>(body.size());
      const int length = data ? static_cast<int>(data->size()) : 0;
      dir.append(reinterpret_cast<const char*>(&offset), 4);
      dir.append(reinterpret_cast<const char*>(&length), 4);
      if (data) body += *data;
    }
    return out + dir + body;
  }

 private:
  std::string textures_, vertices_, meshverts_, faces_;
};

TEST(Q3Bsp, PolygonsMeshesPatchesKeptSkyAndBillboardsSkipped) {
  BspBuilder b;
  const int wall = b.Texture(0), sky = b.Texture(0x4), nodraw = b.Texture(0x80);
  // A quad (type 1) as two triangles through the mesh-vertex list.
  const int q = b.Vertex(0, 0, 0);
  b.Vertex(1, 0, 0);
  b.Vertex(1, 1, 0);
  b.Vertex(0, 1, 0);
  b.Face(wall, 1, q, 4, {0, 1, 2, 0, 2, 3});
  // A triangle mesh (type 3) of one triangle.
  const int t = b.Vertex(0, 0, 5);
  b.Vertex(1, 0, 5);
  b.Vertex(0, 1, 5);
  b.Face(wall, 3, t, 3, {0, 1, 2});
  // Sky and nodraw faces: skipped.
  b.Face(sky, 1, q, 4, {0, 1, 2});
  b.Face(nodraw, 1, q, 4, {0, 1, 2});
  // A 3x3 patch (type 2), a flat arch in z.
  const int p = b.Vertex(0, 0, 10);
  for (int i = 1; i < 9; ++i) b.Vertex(static_cast<float>(i % 3), static_cast<float>(i / 3), 10 + (i % 3 == 1));
  b.Face(wall, 2, p, 9, {}, 3, 3);
  // A billboard (type 4): no geometry.
  b.Face(wall, 4, q, 1, {});

  Q3BspConfig config;
  config.patch_subdivisions = 4;
  Q3BspStats stats;
  absl::StatusOr<Mesh> mesh = ParseQ3Bsp(b.Build(), config, &stats);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->TriangleCount(), 2u + 1u + 2u * 4u * 4u);
  EXPECT_EQ(stats.faces, 6);
  EXPECT_EQ(stats.polygon_faces, 2);
  EXPECT_EQ(stats.patch_faces, 1);
  EXPECT_EQ(stats.skipped_faces, 3);
  // The patch interpolates its corners and bulges to half its middle control point.
  const AABB box = mesh->Bounds();
  EXPECT_EQ(box.lo.z, 0.0f);
  EXPECT_FLOAT_EQ(box.hi.z, 10.5f);
  // Only used vertices remain: 4 + 3 + 25.
  EXPECT_EQ(mesh->vertices.size(), 4u + 3u + 25u);

  config.skip_sky = false;
  config.skip_nodraw = false;
  mesh = ParseQ3Bsp(b.Build(), config, &stats);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->TriangleCount(), 2u + 1u + 32u + 2u);
}

TEST(Q3Bsp, RejectsOtherFilesAndBadIndices) {
  EXPECT_FALSE(ParseQ3Bsp("not a map", Q3BspConfig()).ok());
  BspBuilder b;
  const int wall = b.Texture(0);
  const int v = b.Vertex(0, 0, 0);
  b.Vertex(1, 0, 0);
  b.Vertex(0, 1, 0);
  b.Face(wall, 1, v, 3, {0, 1, 7});  // mesh vertex past the face's vertices
  EXPECT_FALSE(ParseQ3Bsp(b.Build(), Q3BspConfig()).ok());
  std::string wrong = BspBuilder().Build();
  wrong[4] = 47;
  EXPECT_FALSE(ParseQ3Bsp(wrong, Q3BspConfig()).ok());
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
