#include "cc/scenes/refine.h"

#include <cmath>
#include <map>
#include <utility>

#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

Mesh Cube() {
  Mesh m;
  AddBox(m, Vec3(0, 0, 0), Vec3(2, 1, 3));
  return m;  // 12 triangles, closed
}

double Area(const Mesh& m) {
  double total = 0;
  for (const Mesh::Face& f : m.faces) {
    const Vec3 a = m.vertices[f[0]], b = m.vertices[f[1]], c = m.vertices[f[2]];
    const Vec3 u = b - a, v = c - a;
    const double x = double{u.y} * v.z - double{u.z} * v.y, y = double{u.z} * v.x - double{u.x} * v.z,
                 z = double{u.x} * v.y - double{u.y} * v.x;
    total += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return total;
}

// Undirected edge -> number of faces using it.
std::map<std::pair<int, int>, int> EdgeUse(const Mesh& m) {
  std::map<std::pair<int, int>, int> use;
  for (const Mesh::Face& f : m.faces) {
    for (int i = 0; i < 3; ++i) {
      int a = f[i], b = f[(i + 1) % 3];
      if (a > b) std::swap(a, b);
      ++use[{a, b}];
    }
  }
  return use;
}

TEST(Refine, ExactCountSameSurfaceStillClosed) {
  const Mesh in = Cube();
  RefineConfig c;
  c.target_triangles = 1000;  // even remainder: every split is conforming
  const Mesh out = RefineMesh(c, in);
  EXPECT_EQ(out.TriangleCount(), 1000u);
  EXPECT_NEAR(Area(out), Area(in), 1e-6 * Area(in));
  EXPECT_EQ(out.Bounds().lo, in.Bounds().lo);
  EXPECT_EQ(out.Bounds().hi, in.Bounds().hi);
  for (const auto& [edge, n] : EdgeUse(out)) EXPECT_EQ(n, 2) << edge.first << "-" << edge.second;
  // New vertices lie on the box's faces (the surface).
  for (const Vec3& p : out.vertices) {
    const bool on = p.x == 0 || p.x == 2 || p.y == 0 || p.y == 1 || p.z == 0 || p.z == 3;
    EXPECT_TRUE(on) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(Refine, OddRemainderStillExact) {
  RefineConfig c;
  c.target_triangles = 1001;
  const Mesh out = RefineMesh(c, Cube());
  EXPECT_EQ(out.TriangleCount(), 1001u);
  EXPECT_NEAR(Area(out), Area(Cube()), 1e-6 * Area(Cube()));
}

TEST(Refine, LongestEdgesFirstEvensOutSizes) {
  // A long thin box: its 16-unit edges are split before any short one.
  Mesh in;
  AddBox(in, Vec3(0, 0, 0), Vec3(16, 1, 1));
  RefineConfig c;
  c.target_triangles = 12 * 16;
  const Mesh out = RefineMesh(c, in);
  double longest = 0;
  for (const auto& [edge, n] : EdgeUse(out)) {
    const Vec3 d = out.vertices[edge.first] - out.vertices[edge.second];
    longest = std::max(longest, std::sqrt(double{d.x} * d.x + double{d.y} * d.y + double{d.z} * d.z));
  }
  EXPECT_LT(longest, 4.5);  // every edge of 16 units was split at least twice
}

TEST(Refine, DegenerateTrianglesDroppedCountStillExact) {
  Mesh in = Cube();
  const int32_t a = in.AddVertex(Vec3(0, 0, 0)), b = in.AddVertex(Vec3(1, 0, 0)),
                c = in.AddVertex(Vec3(2, 0, 0));
  in.AddTriangle(a, b, c);  // collinear
  in.AddTriangle(a, a, b);  // repeated vertex
  RefineConfig config;
  config.target_triangles = 400;
  const Mesh out = RefineMesh(config, in);
  EXPECT_EQ(out.TriangleCount(), 400u);
  for (const auto& [edge, n] : EdgeUse(out)) EXPECT_EQ(n, 2);
}

TEST(Refine, DeterministicAndNoOpBelowInput) {
  RefineConfig c;
  c.target_triangles = 500;
  EXPECT_EQ(EncodePly(RefineMesh(c, Cube())), EncodePly(RefineMesh(c, Cube())));
  c.target_triangles = 5;
  EXPECT_EQ(RefineMesh(c, Cube()).TriangleCount(), 12u);
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
