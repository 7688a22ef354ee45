#include "cc/scenes/courtyard.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

double MeanTriangles(const std::vector<const Part*>& parts) {
  if (parts.empty()) return 0;
  double sum = 0;
  for (const Part* p : parts) sum += static_cast<double>(p->mesh.faces.size());
  return sum / static_cast<double>(parts.size());
}

const Part* Pick(const std::vector<const Part*>& parts, Rng& rng) {
  return parts.empty() ? nullptr : parts[static_cast<size_t>(rng.UniformInt(static_cast<int64_t>(parts.size())))];
}

// Floor of 1 m tiles (two triangles each) over [x0, x1] x [z0, z1] at y.
void AddTiles(Mesh& m, float x0, float z0, float x1, float z1, float y) {
  const int nx = std::max(1, static_cast<int>(std::lround(x1 - x0)));
  const int nz = std::max(1, static_cast<int>(std::lround(z1 - z0)));
  const int32_t base = static_cast<int32_t>(m.vertices.size());
  for (int j = 0; j <= nz; ++j) {
    for (int i = 0; i <= nx; ++i) m.AddVertex(Vec3(x0 + (x1 - x0) * i / nx, y, z0 + (z1 - z0) * j / nz));
  }
  for (int j = 0; j < nz; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int32_t a = base + j * (nx + 1) + i;
      m.AddQuad(a, a + nx + 1, a + nx + 2, a + 1);
    }
  }
}

}  // namespace

absl::StatusOr<Mesh> GenerateCourtyard(const CourtyardConfig& c, const std::vector<Part>& parts) {
  const std::vector<const Part*> trees = PartsOf(parts, "tree"), plants = PartsOf(parts, "plant"),
                                 tables = PartsOf(parts, "table"), chairs = PartsOf(parts, "chair"),
                                 columns = PartsOf(parts, "column"),
                                 fountains = PartsOf(parts, "fountain");
  if (trees.empty()) return absl::InvalidArgumentError("courtyard: needs a 'tree' part");
  const bool cafes = !tables.empty() && !chairs.empty();
  const double planted = MeanTriangles(trees) + 4 * MeanTriangles(plants);
  const double cafe = MeanTriangles(tables) + 4 * MeanTriangles(chairs) + MeanTriangles(plants);
  const double share = cafes ? c.cafe_share : 0.0;
  const double per_cell = (1 - share) * planted + share * cafe;
  const int n = std::max(1, static_cast<int>(std::ceil(std::sqrt(
                               static_cast<double>(c.target_triangles) / std::max(1.0, per_cell)))));
  const float side = n * c.cell, d = c.arcade_depth;

  Mesh mesh;
  // Frame: tiled courtyard and arcade floors, two storeys of columns, slabs, walls.
  AddTiles(mesh, 0, 0, side, side, 0);
  for (int s = 0; s < 2; ++s) {
    const float y = s * c.storey;
    for (int k = 0; k < 4; ++k) {  // the four wings, as boxes around the courtyard
      const float lo_x = k == 1 ? side : -d, hi_x = k == 3 ? 0 : side + d;
      const float lo_z = k == 2 ? side : -d, hi_z = k == 0 ? 0 : side + d;
      AddBox(mesh, Vec3(lo_x, y + c.storey - 0.3f, lo_z), Vec3(hi_x, y + c.storey, hi_z));  // slab
      const float wx0 = k == 1 ? side + d - 0.3f : (k == 3 ? -d : lo_x);
      const float wx1 = k == 1 ? side + d : (k == 3 ? -d + 0.3f : hi_x);
      const float wz0 = k == 2 ? side + d - 0.3f : (k == 0 ? -d : lo_z);
      const float wz1 = k == 2 ? side + d : (k == 0 ? -d + 0.3f : hi_z);
      AddBox(mesh, Vec3(wx0, y, wz0), Vec3(wx1, y + c.storey, wz1));  // back wall
    }
    // Columns every 3 m along the courtyard's edge.
    const int per_side = std::max(1, static_cast<int>(side / 3));
    for (int k = 0; k < 4; ++k) {
      for (int i = 0; i <= per_side; ++i) {
        const float t = side * i / per_side;
        const Vec3 p = k == 0 ? Vec3(t, y, 0) : k == 1 ? Vec3(side, y, t)
                     : k == 2 ? Vec3(side - t, y, side) : Vec3(0, y, side - t);
        if (!columns.empty()) {
          const Part& col = *columns[(k + i) % columns.size()];
          Place(mesh, col.mesh, p, 0, (c.storey - 0.3f) / col.height);
        } else {
          AddBox(mesh, p + Vec3(-0.2f, 0, -0.2f), p + Vec3(0.2f, c.storey - 0.3f, 0.2f));
        }
      }
    }
  }
  if (static_cast<int64_t>(mesh.faces.size()) > c.target_triangles) {
    return absl::InvalidArgumentError("courtyard: the frame alone passes the target");
  }

  // Cells in a seeded order; the centre one holds the fountain.
  Rng rng(Mix64(c.seed) ^ 0x436f757274ULL);  // "Court"
  std::vector<int> order(static_cast<size_t>(n) * n);
  for (int i = 0; i < n * n; ++i) order[i] = i;
  for (int i = n * n - 1; i > 0; --i) std::swap(order[i], order[rng.UniformInt(i + 1)]);
  const int centre = (n / 2) * n + n / 2;
  for (int cell : order) {
    const Vec3 o((cell % n + 0.5f) * c.cell, 0, (cell / n + 0.5f) * c.cell);
    Mesh m;
    if (cell == centre && !fountains.empty()) {
      Place(m, fountains[0]->mesh, o, 0);
    } else if (cafes && ToUnit(Hash(c.seed, cell, 1)) < share) {
      Place(m, Pick(tables, rng)->mesh, o, rng.Uniform(0, 2 * kPi));
      const Part& chair = *Pick(chairs, rng);
      for (int k = 0; k < 4; ++k) {
        const float a = 0.5f * kPi * k;
        Place(m, chair.mesh, o + Vec3(1.1f * std::cos(a), 0, 1.1f * std::sin(a)), -a - 0.5f * kPi);
      }
      if (const Part* p = Pick(plants, rng)) Place(m, p->mesh, o + Vec3(2.4f, 0, 2.4f), 0);
    } else {
      const Part& tree = *Pick(trees, rng);
      Place(m, tree.mesh, o, rng.Uniform(0, 2 * kPi), rng.Uniform(0.85f, 1.15f));
      for (int k = 0; k < 4 && !plants.empty(); ++k) {
        const float a = 0.5f * kPi * k + 0.25f * kPi;
        Place(m, Pick(plants, rng)->mesh, o + Vec3(2.3f * std::cos(a), 0, 2.3f * std::sin(a)),
              rng.Uniform(0, 2 * kPi));
      }
    }
    if (mesh.faces.size() + m.faces.size() <= static_cast<size_t>(c.target_triangles)) mesh.Append(m);
  }
  // Potted plants along the arcade's back walls while they fit, then a fan.
  const float perimeter = 4 * (side + d);
  int64_t misses = 0;
  for (int64_t i = 0; !plants.empty() && misses < static_cast<int64_t>(plants.size()); ++i) {
    const Part& p = *plants[i % plants.size()];
    if (mesh.faces.size() + p.mesh.faces.size() > static_cast<size_t>(c.target_triangles)) {
      ++misses;
      continue;
    }
    misses = 0;
    const float t = std::fmod(1.2f * static_cast<float>(i), perimeter), q = side + d;
    const int wing = static_cast<int>(t / q);
    const float u = std::fmod(t, q) - d + 0.5f, e = -d + 0.6f;
    const float level = c.storey * static_cast<float>((static_cast<int64_t>(1.2f * i / perimeter)) % 2);
    const Vec3 pos = wing == 0 ? Vec3(u, level, e) : wing == 1 ? Vec3(side - e, level, u)
                   : wing == 2 ? Vec3(side - u, level, side - e) : Vec3(e, level, side - u);
    Place(mesh, p.mesh, pos, 0);
  }
  AddFan(mesh, Vec3(0.5f * side, 0.01f, -0.5f * d), 0.4f, c.target_triangles - static_cast<int64_t>(mesh.faces.size()));
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
