#include "cc/robust/robust_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "cc/kdtree/test_scenes.h"

namespace kdtree {
namespace robust {

float StairZ(int k, float tread) { return static_cast<float>(double(k) * tread); }
float StairY(int k, float rise) { return static_cast<float>(double(k) * rise); }

TriangleSoup Stairs(int steps, float tread, float rise, float width) {
  TriangleSoup s;
  auto quad = [&s](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    s.Add(a, b, c);
    s.Add(a, c, d);
  };
  for (int k = 0; k < steps; ++k) {
    const float z0 = StairZ(k, tread), z1 = StairZ(k + 1, tread);
    const float y0 = StairY(k, rise), y1 = StairY(k + 1, rise);
    quad({0, y0, z0}, {width, y0, z0}, {width, y1, z0}, {0, y1, z0});  // riser k
    quad({0, y1, z0}, {width, y1, z0}, {width, y1, z1}, {0, y1, z1});  // tread k
  }
  return s;
}

TriangleSoup Icosphere(int levels, double radius, const double centre[3]) {
  using V = std::array<double, 3>;
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<V> verts = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                          {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto normalize = [](V v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return V{v[0] / l, v[1] / l, v[2] / l};
  };
  for (V& v : verts) v = normalize(v);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      verts.push_back(normalize(V{verts[a][0] + verts[b][0], verts[a][1] + verts[b][1],
                                  verts[a][2] + verts[b][2]}));
      return mid[key] = static_cast<int>(verts.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(faces.size() * 4);
    for (const auto& f : faces) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    faces = std::move(next);
  }
  std::vector<Vec3> out;
  out.reserve(verts.size());
  for (const V& v : verts) {
    out.emplace_back(static_cast<float>(centre[0] + radius * v[0]),
                     static_cast<float>(centre[1] + radius * v[1]),
                     static_cast<float>(centre[2] + radius * v[2]));
  }
  TriangleSoup soup;
  soup.v.reserve(faces.size() * 3);
  for (const auto& f : faces) soup.Add(out[f[0]], out[f[1]], out[f[2]]);
  return soup;
}

std::vector<std::string> SmallSceneNames() {
  return {"tiny", "stairs", "voxels", "sphere", "thin", "flat", "blocks"};
}

TriangleSoup SmallScene(const std::string& name) {
  if (name == "tiny") {
    TriangleSoup s;
    s.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    s.Add({1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    s.Add({0.5f, 0, -1}, {0.5f, 1, -1}, {0.5f, 0, 1});
    s.Add({0, 0, 0.5f}, {1, 1, 0.5f}, {1, 1.0001f, 0.5f});
    s.Add({-1, -1, -1}, {2, -1, -1}, {-1, 2, 2});
    s.Add({0.25f, 0.25f, -0.5f}, {0.75f, 0.25f, -0.5f}, {0.5f, 0.75f, -0.5f});
    return s;
  }
  if (name == "stairs") return Stairs(8, 0.5f, 0.25f, 2.0f);
  if (name == "voxels") return testing::VoxelGrid(6, 4, 6, 2);
  if (name == "sphere") return testing::BumpySphere(2, 1);
  if (name == "thin") return testing::ThinSoup(300, 3);
  if (name == "flat") return testing::FlatScene(300, 4);
  if (name == "blocks") return testing::VoxelGrid(10, 6, 10, 5);
  return {};
}

TriangleSoup Scaled(const TriangleSoup& soup, double s) {
  TriangleSoup out;
  out.v.reserve(soup.v.size());
  for (const Vec3& p : soup.v) {
    out.v.emplace_back(static_cast<float>(p.x * s), static_cast<float>(p.y * s),
                       static_cast<float>(p.z * s));
  }
  return out;
}

namespace {
std::tuple<float, float, float> Key(const Vec3& p) { return {p.x, p.y, p.z}; }
}  // namespace

std::vector<Vec3> UniqueVertices(const TriangleSoup& soup) {
  std::set<std::tuple<float, float, float>> seen;
  std::vector<Vec3> out;
  for (const Vec3& p : soup.v) {
    if (seen.insert(Key(p)).second) out.push_back(p);
  }
  return out;
}

std::vector<Vec3> EdgeMidpoints(const TriangleSoup& soup) {
  std::set<std::pair<std::tuple<float, float, float>, std::tuple<float, float, float>>> seen;
  std::vector<Vec3> out;
  for (size_t t = 0; t < soup.size(); ++t) {
    const Vec3* v[3] = {&soup.a(t), &soup.b(t), &soup.c(t)};
    for (int e = 0; e < 3; ++e) {
      auto ka = Key(*v[e]), kb = Key(*v[(e + 1) % 3]);
      if (kb < ka) std::swap(ka, kb);
      if (seen.insert({ka, kb}).second) out.push_back((*v[e] + *v[(e + 1) % 3]) * 0.5f);
    }
  }
  return out;
}

std::vector<Ray> AxisParallelRays(const AABB& box, const AxisGrid& grid) {
  std::vector<Ray> rays;
  const Vec3 ext = box.Extent();
  const float margin = 1.0f + std::fmax(ext.x, std::fmax(ext.y, ext.z));
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (const auto& [p, q] : grid.points[a]) {
      for (float sign : {1.0f, -1.0f}) {
        for (int zeros = 0; zeros < 4; ++zeros) {
          Ray r;
          r.origin[a] = sign > 0 ? box.lo[a] - margin : box.hi[a] + margin;
          r.origin[b] = p;
          r.origin[c] = q;
          r.dir[a] = sign;
          r.dir[b] = (zeros & 1) ? -0.0f : 0.0f;
          r.dir[c] = (zeros & 2) ? -0.0f : 0.0f;
          rays.push_back(r);
        }
      }
    }
  }
  return rays;
}

std::vector<float> Sample(const std::vector<float>& v, size_t n) {
  if (v.size() <= n || n < 2) return v;
  std::vector<float> out;
  for (size_t i = 0; i < n; ++i) out.push_back(v[i * (v.size() - 1) / (n - 1)]);
  return out;
}

std::vector<std::pair<float, float>> GridPoints(const std::vector<float>& u,
                                                const std::vector<float>& v, size_t max_points,
                                                size_t sample) {
  std::vector<std::pair<float, float>> out;
  if (u.size() * v.size() <= max_points) {
    for (float a : u) {
      for (float b : v) out.emplace_back(a, b);
    }
    return out;
  }
  const std::vector<float> su = Sample(u, sample), sv = Sample(v, sample);
  std::set<std::pair<float, float>> seen;
  auto add = [&](float a, float b) {
    if (seen.insert({a, b}).second) out.emplace_back(a, b);
  };
  for (float a : u) {
    for (float b : sv) add(a, b);
  }
  for (float b : v) {
    for (float a : su) add(a, b);
  }
  return out;
}

std::vector<float> WithMidpoints(const std::vector<float>& values) {
  std::vector<float> out;
  if (values.empty()) return out;
  out.push_back(values.front() - 0.5f * (1.0f + std::fabs(values.front())));
  for (size_t i = 0; i < values.size(); ++i) {
    out.push_back(values[i]);
    if (i + 1 < values.size()) out.push_back(0.5f * (values[i] + values[i + 1]));
  }
  out.push_back(values.back() + 0.5f * (1.0f + std::fabs(values.back())));
  return out;
}

}  // namespace robust
}  // namespace kdtree
