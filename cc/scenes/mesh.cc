#include "cc/scenes/mesh.h"

#include <cmath>

namespace kdtree {
namespace scenes {

Mat3 Mat3::operator*(const Mat3& o) const {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    }
  }
  return r;
}

Mat3 Mat3::Scale(float s) {
  Mat3 r;
  r.m[0][0] = r.m[1][1] = r.m[2][2] = s;
  return r;
}

Mat3 Mat3::Rotation(int axis, float radians) {
  const float c = std::cos(radians), s = std::sin(radians);
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // the plane rotated in
  Mat3 r;
  r.m[i][i] = c;
  r.m[i][j] = -s;
  r.m[j][i] = s;
  r.m[j][j] = c;
  return r;
}

void Mesh::Append(const Mesh& other, const Mat3& rotation, const Vec3& offset) {
  const int32_t base = static_cast<int32_t>(vertices.size());
  for (const Vec3& p : other.vertices) vertices.push_back(rotation * p + offset);
  for (const Face& f : other.faces) faces.push_back({f[0] + base, f[1] + base, f[2] + base});
}

AABB Mesh::Bounds() const {
  AABB box;
  for (const Face& f : faces) {
    for (int32_t i : f) box.Extend(vertices[i]);
  }
  return box;
}

TriangleSoup Mesh::ToSoup() const {
  TriangleSoup soup;
  soup.v.reserve(3 * faces.size());
  for (const Face& f : faces) soup.Add(vertices[f[0]], vertices[f[1]], vertices[f[2]]);
  return soup;
}

void AddBox(Mesh& mesh, const Vec3& lo, const Vec3& hi) {
  int32_t v[8];
  for (int i = 0; i < 8; ++i) {
    v[i] = mesh.AddVertex({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  mesh.AddQuad(v[0], v[4], v[6], v[2]);  // -x
  mesh.AddQuad(v[1], v[3], v[7], v[5]);  // +x
  mesh.AddQuad(v[0], v[1], v[5], v[4]);  // -y
  mesh.AddQuad(v[2], v[6], v[7], v[3]);  // +y
  mesh.AddQuad(v[0], v[2], v[3], v[1]);  // -z
  mesh.AddQuad(v[4], v[5], v[7], v[6]);  // +z
}

}  // namespace scenes
}  // namespace kdtree
