#include "cc/scenes/subdivide.h"

#include <algorithm>
#include <cmath>

#include "absl/container/flat_hash_map.h"

namespace kdtree {
namespace scenes {
namespace {

Mesh OneLevel(const Mesh& in) {
  Mesh out;
  out.vertices = in.vertices;
  out.faces.reserve(4 * in.faces.size());
  absl::flat_hash_map<uint64_t, int32_t> midpoint;
  midpoint.reserve(2 * in.faces.size());
  auto mid = [&](int32_t a, int32_t b) {
    const uint64_t key =
        (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    const int32_t i = out.AddVertex((in.vertices[a] + in.vertices[b]) * 0.5f);
    midpoint.emplace(key, i);
    return i;
  };
  for (const Mesh::Face& f : in.faces) {
    const int32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
    out.AddTriangle(f[0], ab, ca);
    out.AddTriangle(ab, f[1], bc);
    out.AddTriangle(ca, bc, f[2]);
    out.AddTriangle(ab, bc, ca);
  }
  return out;
}

}  // namespace

int SubdivisionLevels(const SubdivideConfig& config, int64_t input) {
  if (config.target_triangles <= 0) return std::max(0, config.levels);
  if (input <= 0) return 0;
  const double ratio = static_cast<double>(config.target_triangles) / static_cast<double>(input);
  return std::max(0, static_cast<int>(std::lround(std::log(ratio) / std::log(4.0))));
}

Mesh SubdivideMesh(const SubdivideConfig& config, const Mesh& input) {
  Mesh mesh = input;
  const int levels = SubdivisionLevels(config, static_cast<int64_t>(input.faces.size()));
  for (int l = 0; l < levels; ++l) mesh = OneLevel(mesh);
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
