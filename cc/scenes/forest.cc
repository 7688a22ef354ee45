#include "cc/scenes/forest.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

Vec3 RandomUnit(Rng& rng) {
  while (true) {
    const Vec3 p(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
    const float len2 = Dot(p, p);
    if (len2 > 1e-4f && len2 <= 1.0f) return p / std::sqrt(len2);
  }
}

class Forest {
 public:
  explicit Forest(const ForestConfig& c) : c_(c), seed_(Mix64(c.seed ^ 0x466f72657374ULL)) {}

  float Ground(float x, float z) const { return c_.terrain_relief * Fbm2(seed_, x, z, 40.0f, 3); }

  // Square grid of m x m cells over [-half, half]^2.
  void AddTerrain(Mesh& mesh, float half, int m) const {
    const int32_t base = static_cast<int32_t>(mesh.vertices.size());
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= m; ++i) {
        const float x = -half + 2 * half * i / m, z = -half + 2 * half * j / m;
        mesh.AddVertex({x, Ground(x, z), z});
      }
    }
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        const int32_t a = base + j * (m + 1) + i;
        mesh.AddQuad(a, a + m + 1, a + m + 2, a + 1);  // facing +y
      }
    }
  }

  Mesh Tree(Rng& rng, float x, float z) const {
    Mesh m;
    const float height = rng.Uniform(5.0f, 12.0f), r0 = 0.03f * height;
    const float bend_x = rng.Uniform(-0.6f, 0.6f), bend_z = rng.Uniform(-0.6f, 0.6f);
    const Vec3 base(x, Ground(x, z) - 0.3f, z);
    auto axis = [&](float t) { return base + Vec3(bend_x * t * t, height * t, bend_z * t * t); };
    const int sides = std::max(3, c_.trunk_sides), segments = std::max(1, c_.trunk_segments);
    for (int s = 0; s <= segments; ++s) {
      const float t = static_cast<float>(s) / segments, r = r0 * (1.0f - 0.7f * t);
      for (int k = 0; k < sides; ++k) {
        const float a = 2 * kPi * k / sides;
        m.AddVertex(axis(t) + Vec3(r * std::cos(a), 0, r * std::sin(a)));
      }
    }
    for (int s = 0; s < segments; ++s) {
      for (int k = 0; k < sides; ++k) {
        const int k1 = (k + 1) % sides;
        m.AddQuad(s * sides + k, (s + 1) * sides + k, (s + 1) * sides + k1, s * sides + k1);
      }
    }
    const int clusters = 3 + static_cast<int>(rng.UniformInt(4));
    Vec3 centre[6];
    float radius[6];
    for (int k = 0; k < clusters; ++k) {
      centre[k] = axis(rng.Uniform(0.55f, 1.0f)) + RandomUnit(rng) * (0.15f * height);
      radius[k] = height * rng.Uniform(0.12f, 0.22f);
    }
    const int leaves = c_.min_leaves +
                       static_cast<int>(rng.UniformInt(std::max(1, c_.max_leaves - c_.min_leaves)));
    for (int n = 0; n < leaves; ++n) {
      const int k = n % clusters;
      const Vec3 p = centre[k] + RandomUnit(rng) * (radius[k] * std::cbrt(rng.Uniform()));
      const Vec3 u = RandomUnit(rng);
      const Vec3 w = Normalize(Cross(u, RandomUnit(rng)));
      const float s = c_.leaf_size * rng.Uniform(0.7f, 1.3f);
      const int32_t a = m.AddVertex(p), b = m.AddVertex(p + u * s);
      m.AddTriangle(a, b, m.AddVertex(p + (u * 0.5f + w * 0.8f) * s));
    }
    return m;
  }

  void AddGrassBlade(Mesh& mesh, Rng& rng, float half) const {
    const float x = rng.Uniform(-half, half), z = rng.Uniform(-half, half);
    const float yaw = rng.Uniform(0, 2 * kPi), h = rng.Uniform(0.3f, 0.7f);
    const float y = Ground(x, z) - 0.05f;
    const Vec3 side(0.04f * std::cos(yaw), 0, 0.04f * std::sin(yaw));
    const Vec3 lean(rng.Uniform(-0.2f, 0.2f), h, rng.Uniform(-0.2f, 0.2f));
    const int32_t a = mesh.AddVertex(Vec3(x, y, z) - side),
                  b = mesh.AddVertex(Vec3(x, y, z) + side);
    mesh.AddTriangle(a, b, mesh.AddVertex(Vec3(x, y, z) + lean));
  }

 private:
  ForestConfig c_;
  uint64_t seed_;
};

}  // namespace

Mesh GenerateForest(const ForestConfig& c) {
  const Forest forest(c);
  const int64_t target = std::max<int64_t>(c.target_triangles, 1);
  const double tree_tris =
      2.0 * c.trunk_sides * c.trunk_segments + 0.5 * (c.min_leaves + c.max_leaves);
  const int64_t trees = std::max<int64_t>(1, static_cast<int64_t>(0.85 * target / tree_tris));
  const int n = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(trees)))) + 1;
  const float half = 0.5f * n * c.tree_spacing;
  const int cells = std::max(1, std::min(2 * n, static_cast<int>(std::sqrt(target / 10.0))));
  Mesh mesh;
  if (2 * static_cast<int64_t>(cells) * cells <= target) forest.AddTerrain(mesh, half, cells);

  // Trees on a jittered n x n grid, ring by ring from the centre, while they fit.
  const int centre = n / 2;
  bool full = false;
  int rings = 0;
  for (int r = 0; r <= n && !full; ++r) {
    for (int i = centre - r; i <= centre + r && !full; ++i) {
      for (int j = centre - r; j <= centre + r && !full; ++j) {
        if (std::max(std::abs(i - centre), std::abs(j - centre)) != r) continue;
        if (i < 0 || j < 0 || i >= n || j >= n) continue;
        Rng rng(Hash(c.seed ^ 0x7ee5, i, j));
        const float x = -half + (i + 0.5f + rng.Uniform(-0.35f, 0.35f)) * c.tree_spacing;
        const float z = -half + (j + 0.5f + rng.Uniform(-0.35f, 0.35f)) * c.tree_spacing;
        const Mesh tree = forest.Tree(rng, x, z);
        if (static_cast<int64_t>(mesh.faces.size() + tree.faces.size()) > target) {
          full = true;
        } else {
          mesh.Append(tree);
          rings = r + 1;
        }
      }
    }
  }
  // Grass where the trees are (the whole terrain if there are none).
  const float grass_half = rings > 0 ? std::min(half, rings * c.tree_spacing) : half;
  Rng rng(Mix64(c.seed) ^ 0x4772617373ULL);  // "Grass"
  while (static_cast<int64_t>(mesh.faces.size()) < target)
    forest.AddGrassBlade(mesh, rng, grass_half);
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
