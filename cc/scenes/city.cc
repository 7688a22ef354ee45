#include "cc/scenes/city.h"

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

// Boxes of one building on the lot [x0, x0 + lot) x [z0, z0 + lot).
Mesh Building(Rng& rng, const CityConfig& c, float x0, float z0, int max_floors) {
  Mesh m;
  const float lot = c.lot_size, fh = c.floor_height;
  float w = lot * rng.Uniform(0.55f, 0.9f), d = lot * rng.Uniform(0.55f, 0.9f);
  float cx = x0 + 0.5f * lot + rng.Uniform(-0.5f, 0.5f) * (lot - w);
  float cz = z0 + 0.5f * lot + rng.Uniform(-0.5f, 0.5f) * (lot - d);
  const int floors = 2 + static_cast<int>(rng.UniformInt(std::max(1, max_floors - 1)));
  const int tiers = 1 + (floors > 8) + (floors > 16);
  float y = 0;
  for (int t = 0; t < tiers; ++t) {
    const int nf = floors / tiers + (t == 0 ? floors % tiers : 0);
    const float xa = cx - w / 2, xb = cx + w / 2, za = cz - d / 2, zb = cz + d / 2;
    AddBox(m, {xa, y, za}, {xb, y + nf * fh, zb});
    for (int f = 0; f < nf; ++f) {
      const float yf = y + f * fh;
      if (f > 0)
        AddBox(m, {xa - 0.25f, yf - 0.15f, za - 0.25f}, {xb + 0.25f, yf + 0.15f, zb + 0.25f});
      // Window sills on the four facades, centred along each facade.
      const float ys = yf + 0.9f;
      const int nx = std::max(1, static_cast<int>(w / c.window_pitch));
      const int nz = std::max(1, static_cast<int>(d / c.window_pitch));
      for (int i = 0; i < nx; ++i) {
        const float sx = xa + (i + 0.5f) * w / nx;
        AddBox(m, {sx - 0.6f, ys, za - 0.3f}, {sx + 0.6f, ys + 0.12f, za});
        AddBox(m, {sx - 0.6f, ys, zb}, {sx + 0.6f, ys + 0.12f, zb + 0.3f});
      }
      for (int i = 0; i < nz; ++i) {
        const float sz = za + (i + 0.5f) * d / nz;
        AddBox(m, {xa - 0.3f, ys, sz - 0.6f}, {xa, ys + 0.12f, sz + 0.6f});
        AddBox(m, {xb, ys, sz - 0.6f}, {xb + 0.3f, ys + 0.12f, sz + 0.6f});
      }
    }
    y += nf * fh;
    w *= 0.75f;
    d *= 0.75f;
  }
  // Rooftop boxes: water tanks, lift rooms, air conditioners.
  const int extras = 1 + static_cast<int>(rng.UniformInt(3));
  for (int k = 0; k < extras; ++k) {
    const float bw = rng.Uniform(0.8f, 0.3f * w), bd = rng.Uniform(0.8f, 0.3f * d);
    const float bx = cx + rng.Uniform(-0.5f, 0.5f) * (w - bw);
    const float bz = cz + rng.Uniform(-0.5f, 0.5f) * (d - bd);
    AddBox(m, {bx - bw / 2, y, bz - bd / 2},
           {bx + bw / 2, y + rng.Uniform(1.0f, 3.5f), bz + bd / 2});
  }
  return m;
}

// Blocks ordered in square rings around block (0, 0).
std::vector<std::pair<int, int>> Ring(int r) {
  std::vector<std::pair<int, int>> blocks;
  for (int i = -r; i <= r; ++i) {
    for (int j = -r; j <= r; ++j) {
      if (std::max(std::abs(i), std::abs(j)) == r) blocks.push_back({i, j});
    }
  }
  return blocks;
}

}  // namespace

Mesh GenerateCity(const CityConfig& c) {
  Mesh mesh;
  const int64_t target = std::max<int64_t>(c.target_triangles, 2);
  const float block = c.lots_per_side * c.lot_size, pitch = block + c.street_width;
  Rng rng(Mix64(c.seed) ^ 0x43697479ULL);  // "City"
  std::vector<std::pair<int, int>> placed;
  bool full = false;
  for (int r = 0; !full; ++r) {
    const int max_floors = std::max(3, static_cast<int>(c.max_floors / (1.0f + 0.35f * r)));
    for (const auto& [bi, bj] : Ring(r)) {
      if (full) break;
      bool any = false;
      for (int li = 0; li < c.lots_per_side && !full; ++li) {
        for (int lj = 0; lj < c.lots_per_side && !full; ++lj) {
          Rng lot_rng(Hash(c.seed, bi * 64 + li, bj * 64 + lj));
          const Mesh b = Building(lot_rng, c, bi * pitch - block / 2 + li * c.lot_size,
                                  bj * pitch - block / 2 + lj * c.lot_size, max_floors);
          if (static_cast<int64_t>(mesh.faces.size() + b.faces.size()) + 2 > target) {
            full = true;
          } else {
            mesh.Append(b);
            any = true;
          }
        }
      }
      if (any || placed.empty()) placed.push_back({bi, bj});
    }
  }
  // Fill the rest exactly, along the streets west and south of placed blocks.
  auto street_spot = [&](float* x, float* z) {
    const auto& [bi, bj] = placed[rng.UniformInt(static_cast<int64_t>(placed.size()))];
    const float along = rng.Uniform(-0.5f, 0.5f) * block;
    const float across = rng.Uniform(0.1f, 0.9f) * c.street_width;
    if (rng.Uniform() < 0.5f) {
      *x = bi * pitch - block / 2 - across;
      *z = bj * pitch + along;
    } else {
      *x = bi * pitch + along;
      *z = bj * pitch - block / 2 - across;
    }
  };
  float x, z;
  while (static_cast<int64_t>(mesh.faces.size()) + 2 + 12 <= target) {  // bollards
    street_spot(&x, &z);
    AddBox(mesh, {x - 0.15f, 0, z - 0.15f}, {x + 0.15f, 1.0f, z + 0.15f});
  }
  while (static_cast<int64_t>(mesh.faces.size()) + 2 + 2 <= target) {  // road marks
    street_spot(&x, &z);
    const int32_t a = mesh.AddVertex({x - 0.1f, 0.01f, z - 1}),
                  b = mesh.AddVertex({x - 0.1f, 0.01f, z + 1});
    const int32_t e = mesh.AddVertex({x + 0.1f, 0.01f, z + 1}),
                  f = mesh.AddVertex({x + 0.1f, 0.01f, z - 1});
    mesh.AddQuad(a, b, e, f);
  }
  if (static_cast<int64_t>(mesh.faces.size()) + 2 < target) {  // one sign
    street_spot(&x, &z);
    const int32_t a = mesh.AddVertex({x - 0.4f, 2.0f, z}), b = mesh.AddVertex({x + 0.4f, 2.0f, z});
    mesh.AddTriangle(a, b, mesh.AddVertex({x, 2.7f, z}));
  }
  // Ground under the placed blocks and their streets.
  int i0 = placed[0].first, i1 = i0, j0 = placed[0].second, j1 = j0;
  for (const auto& [bi, bj] : placed) {
    i0 = std::min(i0, bi);
    i1 = std::max(i1, bi);
    j0 = std::min(j0, bj);
    j1 = std::max(j1, bj);
  }
  const float margin = block / 2 + c.street_width;
  const float x0 = i0 * pitch - margin, x1 = i1 * pitch + margin;
  const float z0 = j0 * pitch - margin, z1 = j1 * pitch + margin;
  const int32_t a = mesh.AddVertex({x0, 0, z0}), b = mesh.AddVertex({x0, 0, z1});
  const int32_t e = mesh.AddVertex({x1, 0, z1}), f = mesh.AddVertex({x1, 0, z0});
  mesh.AddQuad(a, b, e, f);
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
