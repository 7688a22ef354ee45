#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "cc/scenes/city.h"
#include "cc/scenes/forest.h"
#include "cc/scenes/hairball.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "cc/scenes/subdivide.h"
#include "cc/scenes/teapots.h"
#include "cc/scenes/voxel.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

// A small closed lathe shape standing in for the teapot (no files in tests).
Mesh Pot() {
  Mesh m;
  const int rings = 6, sides = 10;
  for (int r = 0; r < rings; ++r) {
    const float y = static_cast<float>(r), radius = 1.0f + 0.5f * std::sin(0.6f * r);
    for (int s = 0; s < sides; ++s) {
      const float a = 6.2831853f * s / sides;
      m.AddVertex({radius * std::cos(a), y, radius * std::sin(a)});
    }
  }
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < sides; ++s) {
      const int s1 = (s + 1) % sides;
      m.AddQuad(r * sides + s, r * sides + s1, (r + 1) * sides + s1, (r + 1) * sides + s);
    }
  }
  return m;  // 100 triangles
}

void ExpectWellFormed(const Mesh& m) {
  ASSERT_FALSE(m.faces.empty());
  for (const Vec3& p : m.vertices) ASSERT_TRUE(IsFinite(p));
  for (const Mesh::Face& f : m.faces) {
    for (int32_t i : f) {
      ASSERT_GE(i, 0);
      ASSERT_LT(i, static_cast<int32_t>(m.vertices.size()));
    }
  }
}

void ExpectWithinOnePercent(const Mesh& m, int64_t target) {
  const double error = std::fabs(static_cast<double>(m.TriangleCount()) - target) / target;
  EXPECT_LE(error, 0.01) << m.TriangleCount() << " triangles for a target of " << target;
}

HairballConfig SmallHairball(uint64_t seed) {
  HairballConfig c;
  c.target_triangles = 20000;
  c.seed = seed;
  return c;
}

TEST(Hairball, SameSeedSameBytesAndCountNearTarget) {
  const Mesh a = GenerateHairball(SmallHairball(7)), b = GenerateHairball(SmallHairball(7));
  ExpectWellFormed(a);
  EXPECT_EQ(EncodePly(a), EncodePly(b));
  EXPECT_NE(EncodePly(a), EncodePly(GenerateHairball(SmallHairball(8))));
  ExpectWithinOnePercent(a, 20000);
  EXPECT_LE(std::llabs(static_cast<int64_t>(a.TriangleCount()) - 20000), 4);
  // Stays roughly inside the ball.
  const AABB box = a.Bounds();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_GT(box.lo[axis], -1.5f);
    EXPECT_LT(box.hi[axis], 1.5f);
  }
}

VoxelConfig SmallVoxel(int64_t target) {
  VoxelConfig c;
  c.target_triangles = target;
  c.seed = 3;
  return c;
}

TEST(Voxel, SameSeedSameBytesAndCountNearTarget) {
  const Mesh a = GenerateVoxel(SmallVoxel(30000)), b = GenerateVoxel(SmallVoxel(30000));
  ExpectWellFormed(a);
  EXPECT_EQ(EncodePly(a), EncodePly(b));
  ExpectWithinOnePercent(a, 30000);
}

TEST(Voxel, IntegerVerticesAndAxisAlignedUnitFaces) {
  VoxelConfig c = SmallVoxel(0);
  c.width = 40;
  c.depth = 30;
  const Mesh m = GenerateVoxel(c);
  ExpectWellFormed(m);
  for (const Vec3& p : m.vertices) {
    ASSERT_EQ(p.x, std::floor(p.x));
    ASSERT_EQ(p.y, std::floor(p.y));
    ASSERT_EQ(p.z, std::floor(p.z));
  }
  const AABB box = m.Bounds();
  EXPECT_EQ(box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(box.hi.x, 40);
  EXPECT_EQ(box.hi.z, 30);
  for (size_t t = 0; t < m.TriangleCount(); ++t) {
    const Vec3& a = m.vertices[m.faces[t][0]];
    const Vec3& b = m.vertices[m.faces[t][1]];
    const Vec3& d = m.vertices[m.faces[t][2]];
    const Vec3 n = Cross(b - a, d - a);
    // Exactly one component of the normal is non-zero: the face lies in an
    // axis-aligned plane, and its area is half a unit square.
    const int nonzero = (n.x != 0) + (n.y != 0) + (n.z != 0);
    ASSERT_EQ(nonzero, 1) << "triangle " << t;
    ASSERT_EQ(std::fabs(n.x + n.y + n.z), 1.0f) << "triangle " << t;
  }
}

TEST(Voxel, ClosedSurfaceEveryEdgeSharedEvenly) {
  VoxelConfig c = SmallVoxel(0);
  c.width = 24;
  c.depth = 24;
  const Mesh m = GenerateVoxel(c);
  // Sum of face normals of a closed surface is zero.
  double sum[3] = {0, 0, 0};
  for (const Mesh::Face& f : m.faces) {
    const Vec3 n = Cross(m.vertices[f[1]] - m.vertices[f[0]], m.vertices[f[2]] - m.vertices[f[0]]);
    sum[0] += n.x;
    sum[1] += n.y;
    sum[2] += n.z;
  }
  EXPECT_EQ(sum[0], 0);
  EXPECT_EQ(sum[1], 0);
  EXPECT_EQ(sum[2], 0);
}

TEST(Teapots, InstancesOnGroundAndCountNearTarget) {
  TeapotsConfig c;
  c.target_triangles = 20002;
  c.seed = 5;
  const Mesh a = GenerateTeapots(c, Pot()), b = GenerateTeapots(c, Pot());
  ExpectWellFormed(a);
  EXPECT_EQ(EncodePly(a), EncodePly(b));
  EXPECT_EQ(a.TriangleCount(), 200u * 100u + 2u);
  EXPECT_GE(a.Bounds().lo.y, -1e-5f);  // nothing below the ground
  c.input_up_axis = 2;
  ExpectWithinOnePercent(GenerateTeapots(c, Pot()), 20002);
}

TEST(City, ExactCountAndDeterministic) {
  CityConfig c;
  c.target_triangles = 25001;
  c.seed = 11;
  const Mesh a = GenerateCity(c), b = GenerateCity(c);
  ExpectWellFormed(a);
  EXPECT_EQ(a.TriangleCount(), 25001u);
  EXPECT_EQ(EncodePly(a), EncodePly(b));
  EXPECT_GE(a.Bounds().lo.y, 0.0f);
  c.target_triangles = 7;  // smaller than any building: filler only
  EXPECT_EQ(GenerateCity(c).TriangleCount(), 7u);
}

TEST(Forest, ExactCountAndDeterministic) {
  ForestConfig c;
  c.target_triangles = 30000;
  c.seed = 13;
  const Mesh a = GenerateForest(c), b = GenerateForest(c);
  ExpectWellFormed(a);
  EXPECT_EQ(a.TriangleCount(), 30000u);
  EXPECT_EQ(EncodePly(a), EncodePly(b));
  c.target_triangles = 5;
  EXPECT_EQ(GenerateForest(c).TriangleCount(), 5u);
}

TEST(Subdivide, FourTrianglesPerLevelSharedMidpoints) {
  const Mesh pot = Pot();  // 100 triangles, 60 vertices, 160 edges
  SubdivideConfig c;
  c.target_triangles = 1500;  // 1600 is the closest power-of-4 multiple
  EXPECT_EQ(SubdivisionLevels(c, 100), 2);
  const Mesh m = SubdivideMesh(c, pot);
  ExpectWellFormed(m);
  EXPECT_EQ(m.TriangleCount(), 1600u);
  // Level 1: 60 + 160 vertices; level 2: 220 + (2 * 160 + 3 * 100) edges.
  EXPECT_EQ(m.vertices.size(), 220u + 620u);
  // Same surface: the bounding box does not change.
  EXPECT_EQ(m.Bounds().lo, pot.Bounds().lo);
  EXPECT_EQ(m.Bounds().hi, pot.Bounds().hi);
}

TEST(Mesh, ToSoupKeepsTriangles) {
  const Mesh m = GenerateHairball(SmallHairball(1));
  const TriangleSoup soup = m.ToSoup();
  ASSERT_EQ(soup.size(), m.TriangleCount());
  EXPECT_EQ(soup.b(5), m.vertices[m.faces[5][1]]);
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
