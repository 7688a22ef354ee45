// Test support: a hierarchy traced by the leaf-BVH kernels (leaf_bvh.h) --
// the BVH over the kd-tree's leaves, or the BVH over whole triangles
// (triangle_bvh.h) -- against the kd-tree's own traversal, bit for bit.
#ifndef KDTREE_CC_KDTREE_BVH_CHECK_H_
#define KDTREE_CC_KDTREE_BVH_CHECK_H_

#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/tree.h"

namespace kdtree {
namespace testing {

// The lanes of packets of 16 consecutive rays whose closest hit or any hit
// through `bvh` differs from `tree`'s single ray, bit for bit.
int PacketMismatches(const KdTree& tree, const LeafBvh& bvh, const std::vector<Ray>& rays);

struct BvhMismatches {
  int closest = 0;  // single rays' closest hits (and every brute_force_every-th against brute force)
  int any = 0;      // single rays' any hits
  int shadow = 0;   // single shadow rays from the hits, origin triangle untested
  int packets = 0;  // the same rays and shadow rays in packets of 16
  int hits = 0;     // rays with a hit (each spawns a shadow ray)
  int shadows = 0;  // shadow rays blocked
};

// Every query of `rays` through `bvh` against `tree` (built from
// `soup`): closest and any hit, single and in packets; and from each hit a
// shadow ray to a light beyond the box, as the renderer spawns it, leaving
// its origin triangle untested (against the kd-tree searched from the
// light). Every brute_force_every-th closest hit also against brute force.
BvhMismatches CompareWithKdTree(const TriangleSoup& soup, const KdTree& tree, const LeafBvh& bvh,
                                const std::vector<Ray>& rays, int brute_force_every);

}  // namespace testing
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BVH_CHECK_H_
