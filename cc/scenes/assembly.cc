#include "cc/scenes/assembly.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "cc/io/mesh_loader.h"
#include "cc/scenes/assimp_mesh.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

Vec3 Unit(const Vec3& v) {
  const float n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return n > 0 ? v * (1.0f / n) : v;
}

}  // namespace

Mesh NormalisePart(const Mesh& mesh, float height, int up_axis) {
  Mesh m;
  m.Append(mesh, up_axis == 2 ? Mat3::Rotation(0, -kPi / 2) : Mat3(), Vec3(0, 0, 0));
  if (m.vertices.empty()) return m;
  // Bounds of the used vertices only (packaged files carry unused ones).
  AABB box;
  for (const Mesh::Face& f : m.faces) {
    for (int32_t i : f) box.Extend(m.vertices[i]);
  }
  const float h = box.hi.y - box.lo.y;
  const float s = h > 0 ? height / h : 1.0f;
  const Vec3 shift(-(box.lo.x + box.hi.x) / 2, -box.lo.y, -(box.lo.z + box.hi.z) / 2);
  for (Vec3& p : m.vertices) p = (p + shift) * s;
  return m;
}

absl::StatusOr<Part> ReadPart(const std::string& spec) {
  const std::vector<std::string> f = absl::StrSplit(spec, ':');
  Part part;
  int up_axis = 1;
  if (f.size() < 3 || f.size() > 4 || f[0].empty() || !absl::SimpleAtof(f[1], &part.height) ||
      part.height <= 0 || (f.size() == 4 && (!absl::SimpleAtoi(f[3], &up_axis) ||
                                             (up_axis != 1 && up_axis != 2)))) {
    return absl::InvalidArgumentError("part '" + spec + "': want role:height:path[:up_axis]");
  }
  part.role = f[0];
  absl::StatusOr<Mesh> mesh = ReadMesh(f[2]);
  if (!mesh.ok()) return mesh.status();
  part.mesh = NormalisePart(*mesh, part.height, up_axis);
  return part;
}

std::vector<const Part*> PartsOf(const std::vector<Part>& parts, const std::string& role) {
  std::vector<const Part*> out;
  for (const Part& p : parts) {
    if (p.role == role) out.push_back(&p);
  }
  return out;
}

void Place(Mesh& out, const Mesh& part, const Vec3& position, float yaw, float scale) {
  const Mat3 m = Mat3::Rotation(1, yaw) * Mat3::Scale(scale);
  const int32_t base = static_cast<int32_t>(out.vertices.size());
  for (const Vec3& p : part.vertices) out.vertices.push_back(m * p + position);
  for (const Mesh::Face& f : part.faces) {
    // Triangles of zero area (many in CAD tessellations) are left out, as the
    // loader (cc/io) drops them: the count placed is the count loaded.
    if (IsDegenerateTriangle(out.vertices[base + f[0]], out.vertices[base + f[1]],
                             out.vertices[base + f[2]])) {
      continue;
    }
    out.AddTriangle(base + f[0], base + f[1], base + f[2]);
  }
}

void AddTube(Mesh& out, const Vec3& a, const Vec3& b, float radius, int sides, int segments) {
  const Vec3 axis = Unit(b - a);
  const Vec3 helper = std::fabs(axis.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
  const Vec3 u = Unit(Cross(axis, helper)), v = Cross(axis, u);
  const int32_t base = static_cast<int32_t>(out.vertices.size());
  for (int s = 0; s <= segments; ++s) {
    const Vec3 c = a + (b - a) * (static_cast<float>(s) / segments);
    for (int k = 0; k < sides; ++k) {
      const float t = 2 * kPi * k / sides;
      out.AddVertex(c + (u * std::cos(t) + v * std::sin(t)) * radius);
    }
  }
  for (int s = 0; s < segments; ++s) {
    for (int k = 0; k < sides; ++k) {
      const int32_t i0 = base + s * sides + k, i1 = base + s * sides + (k + 1) % sides;
      out.AddQuad(i0, i1, i1 + sides, i0 + sides);
    }
  }
}

void AddFan(Mesh& out, const Vec3& centre, float radius, int64_t n) {
  if (n <= 0) return;
  const int32_t c = out.AddVertex(centre);
  const int32_t first = static_cast<int32_t>(out.vertices.size());
  const int64_t rim = std::max<int64_t>(n, 3);  // n = 1, 2: part of a triangle fan
  for (int64_t k = 0; k < rim; ++k) {
    const float t = 2 * kPi * static_cast<float>(k) / static_cast<float>(rim);
    out.AddVertex(centre + Vec3(radius * std::cos(t), 0, -radius * std::sin(t)));
  }
  for (int64_t k = 0; k < n; ++k) {
    out.AddTriangle(c, first + static_cast<int32_t>(k), first + static_cast<int32_t>((k + 1) % rim));
  }
}

}  // namespace scenes
}  // namespace kdtree
