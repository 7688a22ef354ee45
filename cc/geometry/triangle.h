// Triangle soup: the compact in-memory form every scene is loaded into.
#ifndef KDTREE_CC_GEOMETRY_TRIANGLE_H_
#define KDTREE_CC_GEOMETRY_TRIANGLE_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// Three vertices per triangle, no indexing: triangle i is v[3i], v[3i+1], v[3i+2].
struct TriangleSoup {
  std::vector<Vec3> v;

  size_t size() const { return v.size() / 3; }
  bool empty() const { return v.empty(); }
  const Vec3& a(size_t i) const { return v[3 * i]; }
  const Vec3& b(size_t i) const { return v[3 * i + 1]; }
  const Vec3& c(size_t i) const { return v[3 * i + 2]; }
  void Add(const Vec3& a, const Vec3& b, const Vec3& c) {
    v.push_back(a);
    v.push_back(b);
    v.push_back(c);
  }
  AABB Bounds(size_t i) const {
    AABB box;
    box.Extend(a(i));
    box.Extend(b(i));
    box.Extend(c(i));
    return box;
  }
  AABB Bounds() const {
    AABB box;
    for (const Vec3& p : v) box.Extend(p);
    return box;
  }
};

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_TRIANGLE_H_
