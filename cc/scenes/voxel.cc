#include "cc/scenes/voxel.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr int kHeight = 64;   // blocks per column: one bit each in a uint64_t
constexpr int kPlot = 24;     // building plots are kPlot x kPlot blocks
constexpr int kTreePlot = 8;  // divides kPlot: a tree plot lies in one building plot

int FloorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Bits [lo, hi) of a column, clamped to the column.
uint64_t Bits(int lo, int hi) {
  lo = std::max(lo, 0);
  hi = std::min(hi, kHeight);
  if (lo >= hi) return 0;
  const uint64_t below_hi = hi >= 64 ? ~0ULL : (1ULL << hi) - 1;
  return below_hi & ~((1ULL << lo) - 1);
}

struct Building {
  int x0 = 0, z0 = 0, w = 1, d = 1;  // footprint [x0, x0 + w) x [z0, z0 + d)
  int y0 = 0, floors_height = 1;
};

// The infinite world: every block is a pure function of the seed and position.
class World {
 public:
  explicit World(const VoxelConfig& c) : c_(c), seed_(Mix64(c.seed ^ 0x566f78656cULL)) {}

  int Terrain(int x, int z) const {
    const float f = Fbm2(seed_, static_cast<float>(x), static_cast<float>(z), 96.0f, 4);
    return std::min(48, 14 + static_cast<int>(44.0f * f * std::sqrt(f)));
  }

  bool BuildingIn(int px, int pz, Building* b) const {
    Rng rng(Hash(seed_ ^ 0xb0, px, pz));
    if (rng.Uniform() >= c_.building_density) return false;
    b->w = 6 + static_cast<int>(rng.UniformInt(9));
    b->d = 6 + static_cast<int>(rng.UniformInt(9));
    b->x0 = px * kPlot + 2 + static_cast<int>(rng.UniformInt(kPlot - b->w - 3));
    b->z0 = pz * kPlot + 2 + static_cast<int>(rng.UniformInt(kPlot - b->d - 3));
    b->floors_height = 5 + static_cast<int>(rng.UniformInt(10));
    b->y0 = Terrain(b->x0 + b->w / 2, b->z0 + b->d / 2);
    return true;
  }

  uint64_t Column(int x, int z) const {
    Building b;
    const bool has_building = BuildingIn(FloorDiv(x, kPlot), FloorDiv(z, kPlot), &b);
    int h = Terrain(x, z);
    if (has_building && x >= b.x0 - 1 && x <= b.x0 + b.w && z >= b.z0 - 1 && z <= b.z0 + b.d) {
      h = b.y0;  // flattened ground around the building
    }
    uint64_t column = Bits(0, h);
    for (int y = 1; y < h - 5; ++y) {
      const float n = ValueNoise3(seed_ ^ 0xca4e, static_cast<float>(x),
                                  1.6f * static_cast<float>(y), static_cast<float>(z), 9.0f);
      if (n > c_.cave_threshold) column &= ~(1ULL << y);
    }
    if (has_building) {
      column |= BuildingBits(b, x - b.x0, z - b.z0);
    } else {
      column |= TreeBits(x, z);
    }
    return column;
  }

 private:
  // Hollow box: floor, a slab every 4 blocks, roof, walls with windows and a door.
  static uint64_t BuildingBits(const Building& b, int lx, int lz) {
    if (lx < 0 || lz < 0 || lx >= b.w || lz >= b.d) return 0;
    const int top = b.y0 + b.floors_height;
    uint64_t bits = 0;
    for (int y = b.y0; y <= top; y += 4) bits |= Bits(y, y + 1);
    bits |= Bits(top, top + 1);
    const bool x_wall = lx == 0 || lx == b.w - 1, z_wall = lz == 0 || lz == b.d - 1;
    if (!x_wall && !z_wall) return bits;
    bits |= Bits(b.y0, top + 1);
    if (x_wall && z_wall) return bits;  // corners are solid
    const int along = z_wall ? lx : lz;
    if (along % 3 == 1) {
      for (int y = b.y0 + 2; y < top; y += 4) bits &= ~Bits(y, y + 1);
    }
    if (lz == 0 && lx == b.w / 2) bits &= ~Bits(b.y0 + 1, b.y0 + 3);  // door
    return bits;
  }

  // Trunk and a rounded block of leaves, inside one kTreePlot x kTreePlot plot.
  uint64_t TreeBits(int x, int z) const {
    const int tx = FloorDiv(x, kTreePlot), tz = FloorDiv(z, kTreePlot);
    Rng rng(Hash(seed_ ^ 0x7ee, tx, tz));
    if (rng.Uniform() >= c_.tree_density) return 0;
    const int cx = tx * kTreePlot + 2 + static_cast<int>(rng.UniformInt(4));
    const int cz = tz * kTreePlot + 2 + static_cast<int>(rng.UniformInt(4));
    const int trunk = 4 + static_cast<int>(rng.UniformInt(3));
    const int ground = Terrain(cx, cz), crown = ground + trunk;
    const int dx = std::abs(x - cx), dz = std::abs(z - cz);
    uint64_t bits = 0;
    if (dx == 0 && dz == 0) bits |= Bits(ground, crown);
    if (dx <= 2 && dz <= 2 && !(dx == 2 && dz == 2)) bits |= Bits(crown - 1, crown + 2);
    if (dx <= 1 && dz <= 1) bits |= Bits(crown + 2, crown + 3);
    return bits;
  }

  VoxelConfig c_;
  uint64_t seed_;
};

// Columns of the rectangle [0, nx) x [0, nz); outside it everything is empty.
struct Columns {
  int nx = 0, nz = 0;
  std::vector<uint64_t> bits;
  uint64_t At(int x, int z) const {
    return (x < 0 || z < 0 || x >= nx || z >= nz) ? 0 : bits[static_cast<size_t>(z) * nx + x];
  }
};

Columns Materialise(const World& world, int nx, int nz) {
  Columns c;
  c.nx = nx;
  c.nz = nz;
  c.bits.resize(static_cast<size_t>(nx) * nz);
  for (int z = 0; z < nz; ++z) {
    for (int x = 0; x < nx; ++x) c.bits[static_cast<size_t>(z) * nx + x] = world.Column(x, z);
  }
  return c;
}

int64_t Pop(uint64_t v) { return __builtin_popcountll(v); }

// Exposed faces of column (x, z) when its neighbours are those of `c`.
int64_t ExposedFaces(const Columns& c, int x, int z) {
  const uint64_t b = c.At(x, z);
  return Pop(b & ~(b >> 1)) + Pop(b & ~(b << 1)) + Pop(b & ~c.At(x - 1, z)) +
         Pop(b & ~c.At(x + 1, z)) + Pop(b & ~c.At(x, z - 1)) + Pop(b & ~c.At(x, z + 1));
}

// Triangle counts of every sub-rectangle [0, w) x [0, d) of `c` in O(1) each:
// the faces counted with all of `c` as neighbours, plus the faces that the cut
// at x = w and z = d exposes.
class RectCounter {
 public:
  explicit RectCounter(const Columns& c) : nx_(c.nx), nz_(c.nz) {
    const size_t stride = nx_ + 1;
    area_.assign(stride * (nz_ + 1), 0);
    cut_x_.assign(stride * (nz_ + 1), 0);
    cut_z_.assign(stride * (nz_ + 1), 0);
    for (int z = 0; z < nz_; ++z) {
      for (int x = 0; x < nx_; ++x) {
        const size_t i = (z + 1) * stride + (x + 1);
        area_[i] = ExposedFaces(c, x, z) + area_[i - 1] + area_[i - stride] - area_[i - stride - 1];
        cut_x_[i] = Pop(c.At(x, z) & c.At(x + 1, z)) + cut_x_[i - stride];  // prefix over z
        cut_z_[i] = Pop(c.At(x, z) & c.At(x, z + 1)) + cut_z_[i - 1];       // prefix over x
      }
    }
  }
  int64_t Triangles(int w, int d) const {
    const size_t stride = nx_ + 1;
    return 2 * (area_[d * stride + w] + cut_x_[d * stride + w] + cut_z_[d * stride + w]);
  }

 private:
  int nx_, nz_;
  std::vector<int64_t> area_, cut_x_, cut_z_;
};

// Emits the exposed faces of the rectangle [0, w) x [0, d) of `c`.
Mesh Emit(const Columns& c, int w, int d) {
  Mesh mesh;
  absl::flat_hash_map<uint64_t, int32_t> index;
  auto vertex = [&](int x, int y, int z) {
    const uint64_t key = (static_cast<uint64_t>(x) << 40) | (static_cast<uint64_t>(y) << 32) |
                         static_cast<uint64_t>(z);
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int32_t i =
        mesh.AddVertex(Vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
    index.emplace(key, i);
    return i;
  };
  auto inside = [&](int x, int z) { return x >= 0 && z >= 0 && x < w && z < d; };
  // Faces -x, +x, -y, +y, -z, +z: the unit square's corners as offsets from
  // the block's minimum corner, counter-clockwise seen from outside.
  static const int kCorner[6][4][3] = {
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  for (int z = 0; z < d; ++z) {
    for (int x = 0; x < w; ++x) {
      const uint64_t b = c.At(x, z);
      if (b == 0) continue;
      uint64_t open[6];  // blocks whose face k (kCorner order) is exposed
      open[0] = b & ~(inside(x - 1, z) ? c.At(x - 1, z) : 0);
      open[1] = b & ~(inside(x + 1, z) ? c.At(x + 1, z) : 0);
      open[2] = b & ~(b << 1);
      open[3] = b & ~(b >> 1);
      open[4] = b & ~(inside(x, z - 1) ? c.At(x, z - 1) : 0);
      open[5] = b & ~(inside(x, z + 1) ? c.At(x, z + 1) : 0);
      for (int y = 0; y < kHeight; ++y) {
        if (!((b >> y) & 1)) continue;
        for (int k = 0; k < 6; ++k) {
          if (!((open[k] >> y) & 1)) continue;
          int32_t v[4];
          for (int q = 0; q < 4; ++q) {
            v[q] = vertex(x + kCorner[k][q][0], y + kCorner[k][q][1], z + kCorner[k][q][2]);
          }
          mesh.AddQuad(v[0], v[1], v[2], v[3]);
        }
      }
    }
  }
  return mesh;
}

}  // namespace

Mesh GenerateVoxel(const VoxelConfig& config) {
  const World world(config);
  if (config.target_triangles <= 0) {
    const int w = std::max(1, config.width), d = std::max(1, config.depth);
    return Emit(Materialise(world, w, d), w, d);
  }
  // Triangles per column from a sample, then a world big enough for any
  // rectangle the search may pick.
  const int sample = 64;
  const int64_t sample_tris =
      RectCounter(Materialise(world, sample, sample)).Triangles(sample, sample);
  const double per_column =
      std::max<double>(1.0, static_cast<double>(sample_tris) / (sample * sample));
  const int side = std::max(2, static_cast<int>(std::sqrt(config.target_triangles / per_column)));
  const int max_side = side * 3 / 2 + 8;
  const Columns columns = Materialise(world, max_side, max_side);
  const RectCounter counter(columns);
  int best_w = 1, best_d = 1;
  int64_t best_err = -1;
  for (int w = std::max(1, side * 2 / 3); w <= max_side; ++w) {
    for (int d = std::max(1, w * 3 / 4); d <= std::min(max_side, w * 4 / 3 + 1); ++d) {
      const int64_t err = std::llabs(counter.Triangles(w, d) - config.target_triangles);
      if (best_err < 0 || err < best_err) {
        best_err = err;
        best_w = w;
        best_d = d;
      }
    }
  }
  return Emit(columns, best_w, best_d);
}

}  // namespace scenes
}  // namespace kdtree
