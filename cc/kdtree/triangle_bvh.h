// A bounding-volume hierarchy over whole triangles, with no kd-tree: the
// baseline that says what the kd-tree's leaves cost our fastest mode.
//
// Why. The kd-tree's packets (kd_bvh_packet: the kd-tree's leaves under a
// BVH, leaf_bvh.h) trace camera rays slower than Embree's on most scenes.
// The two differ in their structure (a kd leaf holds a fragment of every
// triangle that crosses its cell, 1.76 references a triangle on sah-packet,
// and a camera packet tests 16 to 32 triangles a leaf; Embree's BVH holds
// each triangle once, in leaves of a few) and in their kernels (ours exact,
// Embree's not). This hierarchy has Embree's kind of structure and is
// traced by our kernels unchanged (leaf_bvh.h's IntersectLeafBvh,
// OccludedLeafBvh and their packet versions), so that render_bench's
// tri_bvh and tri_bvh_packet separate the two: what they gain over kd_bvh
// and kd_bvh_packet is the kd-tree's structure, what they still lack
// against Embree is the kernel. It is not a kd-tree and not one of the
// report's variants.
//
// Build: top-down binned SAH over the triangles' centroids (Wald, "On fast
// construction of SAH-based bounding volume hierarchies", RT 2007;
// MacDonald & Booth's surface area heuristic, The Visual Computer 6(3),
// 1990), costs counted in leaf packets of four triangles as the leaf test
// runs them, a leaf where the SAH prefers it; then collapsed into eight-wide
// nodes as the kd-tree's BVH is (wide_collapse.h). Each triangle is in
// exactly one leaf, stored in leaf_layout.h's packets.
//
// Exactness: a triangle's box holds it whole, and the traversal and the leaf
// test are the kd-tree's BVH's (leaf_bvh.h: a conservative box test, the
// exact watertight test, Closer's tie rule), so each ray gets the kd-tree's
// answer, bit for bit (triangle_bvh_test.cc; render_bench's validation).
#ifndef KDTREE_CC_KDTREE_TRIANGLE_BVH_H_
#define KDTREE_CC_KDTREE_TRIANGLE_BVH_H_

#include <cstddef>

#include "absl/status/statusor.h"

#include "cc/geometry/triangle.h"
#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

struct TriangleBvhOptions {
  int bins = 32;  // SAH candidates per axis: bins - 1 planes between centroid bins
  // A node of more triangles is always split; one of at most this many
  // becomes a leaf when the SAH says so (four or fewer: always). In paired
  // rounds (render_bench, bunny, city2, hairball-1m, courtyard-1m; 2026-12-07)
  // leaves of at most four gave hairball-1m a tree of twice the nodes and
  // 0.87 of Embree's best mode, against 1.02 with 16.
  int max_leaf = 16;
  float traversal_cost = 1.0f;  // a node step, in leaf-packet tests
};

// The hierarchy over `soup`'s triangles (an empty one for an empty soup).
// Errors: builder.h's CheckBuildInput, as BuildKdTree's.
absl::StatusOr<LeafBvh> BuildTriangleBvh(const TriangleSoup& soup,
                                         const TriangleBvhOptions& options = {});

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TRIANGLE_BVH_H_
