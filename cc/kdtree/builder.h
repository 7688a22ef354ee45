// Top-down recursive kd-tree construction (the report's sections "Spatial
// median kd-tree" to "Pruning"): one driver, with the split strategy (median
// or binned SAH), clipping and pruning switched by Config.
#ifndef KDTREE_CC_KDTREE_BUILDER_H_
#define KDTREE_CC_KDTREE_BUILDER_H_

#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

// Builds the tree over `soup`. Rules (see config.h for the options):
//  - root box = union of the triangles' tight boxes; root depth 0;
//  - leaf when the node holds <= maxLeafSize references or depth >= maxDepth,
//    or when the strategy finds no plane (a node box of zero extent);
//  - partition: a reference goes left when box.lo < P, right when box.hi > P
//    (strict: a box that only touches the plane goes to one side). A box lying
//    in the plane (lo == hi == P) goes to both children by default; the
//    seed-compatible mode sends it nowhere and counts it in lost_planar, as the
//    report's numbers show its implementation did;
//  - node and reference arrays are reserved up front (8x the triangle count:
//    address space, only the pages written are backed); build references
//    live in one pool reused by every level, so the build does no per-node
//    heap allocation.
// Beyond the report (config.h): full-SAH cost termination and the depth cap
// 8 + 1.3 log2 N; the sweep and hybrid split searches; perfect splits; leaf
// pruning off (box-only); the collapse post-pass; and a parallel build
// (buildThreads) that writes the same tree as the serial one.
// What a build may hold. A tree's size is not bounded by the triangle count:
// with a deep maxDepth, triangles that straddle many split planes (a spatial
// median on a small mesh) are referenced in exponentially many leaves. So the
// build counts what it has made, at the size it has when the lists and the
// finished tree are both held (nodes twice; each leaf's list and its packets
// of four triangles, leaf_layout.h), and fails once that passes max_bytes.
struct BuildLimits {
  uint64_t max_bytes = 0;  // 0: no limit but the 2^30 index range
};

// What every builder (this one, triangle_bvh.h's) refuses of its input: a
// soup whose size is not a multiple of 3, 2^30 - 1 triangles or more, or a
// non-finite vertex (InvalidArgument naming the triangle; the loaders drop
// such triangles).
absl::Status CheckBuildInput(const TriangleSoup& soup);

// Errors: invalid config, CheckBuildInput's, more than 2^30 nodes or refs
// or 2^30 - 1 leaf packets, or a tree over limits.max_bytes
// (ResourceExhausted, saying where it stopped).
absl::StatusOr<KdTree> BuildKdTree(const TriangleSoup& soup, const Config& config,
                                   const BuildLimits& limits = {});

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BUILDER_H_
