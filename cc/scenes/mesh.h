// Indexed triangle mesh: what the scene generators build and the PLY writer
// stores. Vertices are float32 (as every loader reads them); faces index them.
#ifndef KDTREE_CC_SCENES_MESH_H_
#define KDTREE_CC_SCENES_MESH_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/geometry/triangle.h"
#include "cc/geometry/vec3.h"

namespace kdtree {
namespace scenes {

// The most a scene tool reads of one input file (meshes: assimp_mesh.h; maps
// and tracks: cc/base/read_file.h): 2 GiB, above every input of the full
// profile.
inline constexpr size_t kSceneInputBudget = size_t{2} << 30;

// 3x3 matrix (row-major) for the rotations and scales of instanced objects.
struct Mat3 {
  float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z,
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z};
  }
  Mat3 operator*(const Mat3& o) const;

  static Mat3 Scale(float s);
  // Right-handed rotation by `radians` about the unit axis 0 (x), 1 (y), 2 (z).
  static Mat3 Rotation(int axis, float radians);
};

struct Mesh {
  using Face = std::array<int32_t, 3>;
  std::vector<Vec3> vertices;
  std::vector<Face> faces;

  size_t TriangleCount() const { return faces.size(); }

  int32_t AddVertex(const Vec3& p) {
    vertices.push_back(p);
    return static_cast<int32_t>(vertices.size() - 1);
  }
  void AddTriangle(int32_t a, int32_t b, int32_t c) { faces.push_back({a, b, c}); }
  // Quad a-b-c-d (counter-clockwise seen from its front) as triangles abc, acd.
  void AddQuad(int32_t a, int32_t b, int32_t c, int32_t d) {
    AddTriangle(a, b, c);
    AddTriangle(a, c, d);
  }
  // Appends `other` transformed by p -> rotation * p + offset.
  void Append(const Mesh& other, const Mat3& rotation, const Vec3& offset);
  void Append(const Mesh& other) { Append(other, Mat3(), Vec3(0, 0, 0)); }

  AABB Bounds() const;
  // Un-indexed copy in the project's in-memory form.
  TriangleSoup ToSoup() const;
};

// Closed axis-aligned box (12 triangles, outward-facing).
void AddBox(Mesh& mesh, const Vec3& lo, const Vec3& hi);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_MESH_H_
