// Triangle data stored in leaf order, 4 triangles per packet, for traversal.
//
// Wald, "Realtime Ray Tracing and Interactive Global Illumination", PhD
// thesis, Saarland University, 2004, section 7.1: the triangles a leaf
// references are best stored with the leaf, so that the leaf's tests read one
// contiguous block instead of chasing an index per triangle into an array in
// input order (one likely cache miss per triangle); and in packets of 4 as a
// structure of arrays, so that one SIMD test covers 4 triangles (the layout of
// Embree's triangle4, Wald et al., "Embree", ACM TOG 33(4), 2014).
//
// The data are the triangles' vertices exactly as in the soup
// (KdTree::verts), because the watertight test (cc/geometry/watertight.h)
// must see the very floats of the shared vertices: a precomputed edge form
// (v0 + e1, or Woop's unit-triangle transform) would round differently and
// change the answers. So results are identical with or without the layout.
//
// Packet layout (floats): [vertex v][axis k][lane l] at (3 v + k) * 4 + l,
// v = 0, 1, 2 for a, b, c. Lanes past a leaf's count are zero (the traversal
// masks them). Leaf j's lane l is the triangle refs[leaf.index() + 1 + 4 j + l].
#ifndef KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
#define KDTREE_CC_KDTREE_LEAF_LAYOUT_H_

#include <cstddef>
#include <cstdint>

#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr int kPacketLanes = 4;
inline constexpr int kPacketFloats = 9 * kPacketLanes;

// Fills tree->leaf_soa and tree->leaf_packet from the nodes, refs and verts
// (replacing any previous layout). A tree without verts gets none.
void LayoutLeafTriangles(KdTree* tree);

// Whether `tree` has a complete layout (the traversal uses it then).
inline bool HasLeafLayout(const KdTree& tree) {
  return !tree.leaf_packet.empty() && tree.leaf_packet.size() == tree.nodes.size();
}

// Bytes held by the layout (0 when absent).
inline size_t LeafLayoutBytes(const KdTree& tree) {
  return tree.leaf_soa.size() * sizeof(float) + tree.leaf_packet.size() * sizeof(uint32_t);
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
