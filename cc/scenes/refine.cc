#include "cc/scenes/refine.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/inlined_vector.h"
#include "cc/io/mesh_loader.h"

namespace kdtree {
namespace scenes {
namespace {

uint64_t EdgeKey(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

double LengthSquared(const Vec3& a, const Vec3& b) {
  const double dx = double{a.x} - b.x, dy = double{a.y} - b.y, dz = double{a.z} - b.z;
  return dx * dx + dy * dy + dz * dz;
}

class Refiner {
 public:
  explicit Refiner(const Mesh& input) : mesh_(input) {
    edges_.reserve(3 * mesh_.faces.size());
    for (int32_t f = 0; f < static_cast<int32_t>(mesh_.faces.size()); ++f) {
      const Mesh::Face& face = mesh_.faces[f];
      for (int i = 0; i < 3; ++i) AddEdge(face[i], face[(i + 1) % 3], f);
    }
  }

  Mesh Run(int64_t target) {
    mesh_.faces.reserve(static_cast<size_t>(target));
    mesh_.vertices.reserve(mesh_.vertices.size() + static_cast<size_t>(target) / 2 + 1);
    while (static_cast<int64_t>(mesh_.faces.size()) < target && !heap_.empty()) {
      const uint64_t key = heap_.top().second;
      heap_.pop();
      auto it = edges_.find(key);
      if (it == edges_.end()) continue;  // already split
      const int64_t room = target - static_cast<int64_t>(mesh_.faces.size());
      absl::InlinedVector<int32_t, 2> faces = it->second;
      if (static_cast<int64_t>(faces.size()) > room) faces.resize(static_cast<size_t>(room));
      Split(key, faces);
    }
    return std::move(mesh_);
  }

 private:
  void AddEdge(int32_t a, int32_t b, int32_t face) {
    if (a == b) return;  // degenerate input triangle: never split there
    const uint64_t key = EdgeKey(a, b);
    auto [it, inserted] = edges_.try_emplace(key);
    it->second.push_back(face);
    if (inserted) heap_.emplace(LengthSquared(mesh_.vertices[a], mesh_.vertices[b]), key);
  }

  void ReplaceFace(int32_t a, int32_t b, int32_t from, int32_t to) {
    auto it = edges_.find(EdgeKey(a, b));
    if (it == edges_.end()) return;
    for (int32_t& f : it->second) {
      if (f == from) f = to;
    }
  }

  // Splits edge `key` at its midpoint in each of `faces` (all of the edge's
  // faces, or fewer for the last, non-conforming split).
  void Split(uint64_t key, const absl::InlinedVector<int32_t, 2>& faces) {
    const int32_t a = static_cast<int32_t>(key >> 32), b = static_cast<int32_t>(key & 0xffffffffu);
    const int32_t m = mesh_.AddVertex((mesh_.vertices[a] + mesh_.vertices[b]) * 0.5f);
    edges_.erase(key);
    for (const int32_t f : faces) {
      const Mesh::Face face = mesh_.faces[f];
      int i = 0;
      while (i < 3 && EdgeKey(face[i], face[(i + 1) % 3]) != key) ++i;
      if (i == 3) continue;
      const int32_t u = face[i], v = face[(i + 1) % 3], w = face[(i + 2) % 3];
      const int32_t g = static_cast<int32_t>(mesh_.faces.size());
      mesh_.faces[f] = {u, m, w};
      mesh_.faces.push_back({m, v, w});
      ReplaceFace(v, w, f, g);
      AddEdge(u, m, f);
      AddEdge(m, v, g);
      AddEdge(m, w, f);
      edges_[EdgeKey(m, w)].push_back(g);
    }
  }

  Mesh mesh_;
  absl::flat_hash_map<uint64_t, absl::InlinedVector<int32_t, 2>> edges_;
  // Longest first; equal lengths by key, so the order is deterministic.
  std::priority_queue<std::pair<double, uint64_t>> heap_;
};

}  // namespace

namespace {

// Drops triangles of zero area (the loader, cc/io, drops them too).
int64_t DropDegenerate(Mesh& mesh) {
  const size_t before = mesh.faces.size();
  mesh.faces.erase(std::remove_if(mesh.faces.begin(), mesh.faces.end(),
                                  [&](const Mesh::Face& f) {
                                    return IsDegenerateTriangle(mesh.vertices[f[0]],
                                                                mesh.vertices[f[1]],
                                                                mesh.vertices[f[2]]);
                                  }),
                   mesh.faces.end());
  return static_cast<int64_t>(before - mesh.faces.size());
}

}  // namespace

Mesh RefineMesh(const RefineConfig& config, const Mesh& input) {
  Mesh clean = input;
  DropDegenerate(clean);
  if (config.target_triangles <= static_cast<int64_t>(clean.faces.size())) return clean;
  // Splitting a sliver can round a half to zero area; aim higher by what was
  // lost and run again (deterministic; one extra round in practice).
  int64_t aim = config.target_triangles;
  for (int round = 0; round < 8; ++round) {
    Mesh out = Refiner(clean).Run(aim);
    const int64_t lost = DropDegenerate(out);
    const int64_t have = static_cast<int64_t>(out.faces.size());
    if (have == config.target_triangles) return out;
    if (lost == 0 || have > config.target_triangles) {
      out.faces.resize(static_cast<size_t>(std::min(have, config.target_triangles)));
      return out;
    }
    aim += config.target_triangles - have;
  }
  Mesh out = Refiner(clean).Run(aim);
  DropDegenerate(out);
  return out;
}

}  // namespace scenes
}  // namespace kdtree
