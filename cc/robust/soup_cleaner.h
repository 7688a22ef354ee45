// Input hygiene for a triangle soup built in memory (generated scenes, or
// meshes that did not come through LoadMesh): drops the triangles the loader
// drops (cc/io/mesh_loader.h), with counts.
//  - not IsSaneTriangle: a NaN/Inf coordinate or |c| > kMaxAbsCoordinate;
//  - IsDegenerateTriangle: zero area in exact arithmetic (repeated or
//    collinear vertices). The watertight test never hits these either
//    (cc/geometry/exact_area.h), the fast one almost never; dropping them
//    saves the tree the references.
#ifndef KDTREE_CC_ROBUST_SOUP_CLEANER_H_
#define KDTREE_CC_ROBUST_SOUP_CLEANER_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/geometry/triangle.h"

namespace kdtree {

struct CleanReport {
  size_t kept = 0;
  size_t dropped_nonfinite = 0;   // NaN, Inf or absurd coordinates
  size_t dropped_degenerate = 0;  // exactly zero area
  std::vector<uint32_t> original_index;  // for each kept triangle, its index in the input
};

// The soup without the triangles described above; triangle order is kept.
TriangleSoup CleanSoup(const TriangleSoup& soup, CleanReport* report);

}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_SOUP_CLEANER_H_
