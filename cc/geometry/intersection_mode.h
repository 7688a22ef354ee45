// Which ray-triangle test a tracer runs: the watertight one (default) or the
// fast Moeller-Trumbore one (kept so that the cost of robustness can be
// measured on the very same rays).
#ifndef KDTREE_CC_GEOMETRY_INTERSECTION_MODE_H_
#define KDTREE_CC_GEOMETRY_INTERSECTION_MODE_H_

namespace kdtree {

enum class IntersectionMode {
  // Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1),
  // 2013 (watertight.h): a ray through a shared edge or vertex of a closed
  // mesh always hits one of its triangles. The default everywhere.
  kWatertight,
  // Moeller & Trumbore 1997 (intersect.h): faster, may miss on shared edges.
  kFast,
};

inline const char* IntersectionModeName(IntersectionMode mode) {
  return mode == IntersectionMode::kWatertight ? "watertight" : "fast";
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_INTERSECTION_MODE_H_
