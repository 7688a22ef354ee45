#include "cc/kdtree/test_scenes.h"

#include <cmath>
#include <cstring>
#include <array>
#include <map>
#include <random>
#include <utility>

#include "cc/geometry/spawn.h"

namespace kdtree {
namespace testing {

TriangleSoup BumpySphere(int levels, uint32_t seed) {
  const float p = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> verts = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0},
                             {0, -1, p}, {0, 1, p}, {0, -1, -p}, {0, 1, -p},
                             {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& v : verts) v = Normalize(v);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      verts.push_back(Normalize((verts[a] + verts[b]) * 0.5f));
      return mid[key] = static_cast<int>(verts.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : faces) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    faces = std::move(next);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> bump(0.9f, 1.1f);
  for (Vec3& v : verts) v = v * bump(rng);
  TriangleSoup soup;
  for (const auto& f : faces) soup.Add(verts[f[0]], verts[f[1]], verts[f[2]]);
  return soup;
}

TriangleSoup VoxelGrid(int nx, int ny, int nz, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<char> solid(static_cast<size_t>(nx) * ny * nz);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        // A terrain: columns of random height, plus a few floating blocks.
        const int h = 1 + static_cast<int>((x * 7 + z * 13 + static_cast<int>(rng() % 3)) % ny) / 2;
        solid[(static_cast<size_t>(z) * ny + y) * nx + x] = (y < h) || (rng() % 23 == 0);
      }
    }
  }
  auto at = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return false;
    return solid[(static_cast<size_t>(z) * ny + y) * nx + x] != 0;
  };
  TriangleSoup soup;
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    soup.Add(a, b, c);
    soup.Add(a, c, d);
  };
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        if (!at(x, y, z)) continue;
        const float X = x, Y = y, Z = z;
        if (!at(x - 1, y, z)) quad({X, Y, Z}, {X, Y, Z + 1}, {X, Y + 1, Z + 1}, {X, Y + 1, Z});
        if (!at(x + 1, y, z))
          quad({X + 1, Y, Z}, {X + 1, Y + 1, Z}, {X + 1, Y + 1, Z + 1}, {X + 1, Y, Z + 1});
        if (!at(x, y - 1, z)) quad({X, Y, Z}, {X + 1, Y, Z}, {X + 1, Y, Z + 1}, {X, Y, Z + 1});
        if (!at(x, y + 1, z))
          quad({X, Y + 1, Z}, {X, Y + 1, Z + 1}, {X + 1, Y + 1, Z + 1}, {X + 1, Y + 1, Z});
        if (!at(x, y, z - 1)) quad({X, Y, Z}, {X, Y + 1, Z}, {X + 1, Y + 1, Z}, {X + 1, Y, Z});
        if (!at(x, y, z + 1))
          quad({X, Y, Z + 1}, {X + 1, Y, Z + 1}, {X + 1, Y + 1, Z + 1}, {X, Y + 1, Z + 1});
      }
    }
  }
  return soup;
}

TriangleSoup ThinSoup(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), len(-0.1f, 0.1f), small(-0.002f, 0.002f);
  TriangleSoup soup;
  for (int i = 0; i < count; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b = a + Vec3(len(rng), len(rng), len(rng));
    const Vec3 c = (a + b) * 0.5f + Vec3(small(rng), small(rng), small(rng));
    soup.Add(a, b, c);
  }
  return soup;
}

TriangleSoup FlatScene(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 10.0f), s(0.1f, 1.0f);
  TriangleSoup soup;
  for (int i = 0; i < count; ++i) {
    const Vec3 a(u(rng), u(rng), 0);
    soup.Add(a, a + Vec3(s(rng), 0, 0), a + Vec3(0, s(rng), 0));
  }
  return soup;
}

std::vector<Ray> RandomRays(const TriangleSoup& soup, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const AABB box = soup.Bounds();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  const float radius = Length(box.Extent()) * 0.75f + 1e-3f;
  auto sphere = [&]() {
    for (;;) {
      const Vec3 d(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
      if (Dot(d, d) <= 1.0f && Dot(d, d) > 1e-6f) return Normalize(d);
    }
  };
  std::vector<Ray> rays;
  rays.reserve(count);
  for (int i = 0; i < count; ++i) {
    Ray r;
    r.origin = centre + sphere() * (radius * (0.2f + u(rng)));
    if (i % 2 == 0 && !soup.empty()) {
      const size_t t = rng() % soup.size();
      float b1 = u(rng), b2 = u(rng);
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      const Vec3 target = soup.a(t) + (soup.b(t) - soup.a(t)) * b1 + (soup.c(t) - soup.a(t)) * b2;
      r.dir = target - r.origin;
    } else {
      r.dir = sphere();
    }
    if (i % 7 == 3) r.tmax = u(rng) * radius * 2;  // a finite interval, like a shadow ray
    rays.push_back(r);
  }
  return rays;
}

std::vector<Ray> CameraRays(const TriangleSoup& soup, int width, int height) {
  const AABB box = soup.Bounds();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  const Vec3 ext = box.Extent();
  const float size = std::fmax(std::fmax(ext.x, ext.y), std::fmax(ext.z, 1e-3f));
  const Vec3 eye = centre + Vec3(0.1f * size, 0.2f * size, ext.z * 0.5f + 1.4f * size);
  const Vec3 forward = Normalize(centre - eye);
  const Vec3 right = Normalize(Cross(forward, Vec3(0, 1, 0)));
  const Vec3 up = Cross(right, forward);
  const float half = std::tan(22.5f * 3.14159265f / 180.0f);
  std::vector<Ray> rays;
  rays.reserve(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float sx = (2.0f * (x + 0.5f) / width - 1.0f) * half;
      const float sy = (1.0f - 2.0f * (y + 0.5f) / height) * half;
      rays.push_back(Ray{eye, forward + right * sx + up * sy});
    }
  }
  return rays;
}

TriangleSoup NamedScene(const std::string& name) {
  if (name == "sphere") return BumpySphere(4, 1);
  if (name == "voxels") return VoxelGrid(10, 6, 10, 2);
  if (name == "thin") return ThinSoup(2000, 3);
  if (name == "flat") return FlatScene(1000, 4);
  return {};
}

std::vector<Ray> GridAxisRays(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cell(-1, 11), axis(0, 2), sign(0, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r;
    for (int k = 0; k < 3; ++k) {
      r.origin[k] = static_cast<float>(cell(rng)) + (sign(rng) ? 0.5f : 0.0f);
      r.dir[k] = sign(rng) ? 0.0f : -0.0f;
    }
    r.dir[axis(rng)] = sign(rng) ? 1.0f : -1.0f;
    rays.push_back(r);
  }
  return rays;
}

Ray ShadowRayFromHit(const TriangleSoup& soup, const Hit& hit, const Vec3& light) {
  const Vec3 &a = soup.a(hit.tri), &b = soup.b(hit.tri), &c = soup.c(hit.tri);
  return SpawnShadowRay(HitPointWithError(a, b, c, hit.u, hit.v), GeometricNormal(a, b, c),
                        light);
}

bool BitwiseSameHit(const Hit& a, const Hit& b) {
  return a.tri == b.tri && std::memcmp(&a.t, &b.t, sizeof(float)) == 0 &&
         std::memcmp(&a.u, &b.u, sizeof(float)) == 0 &&
         std::memcmp(&a.v, &b.v, sizeof(float)) == 0;
}

}  // namespace testing
}  // namespace kdtree
