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
// Packet layout (40 words): [vertex v][axis k][lane l] at (3 v + k) * 4 + l,
// v = 0, 1, 2 for a, b, c (36 floats), then the 4 lanes' triangle indices
// (uint32 bit patterns, read with memcpy or SSE integer loads). A leaf's
// packets are consecutive; lane 0's index has bit 31 set in the leaf's last
// packet; lanes past a leaf's count hold index kPadLane and zero vertices
// (the traversal masks them). Leaf j's lane l is the triangle
// refs[leaf.index() + 1 + 4 j + l].
//
// The traversal walks tree.leaf_nodes, a copy of tree.nodes in which a leaf's
// index is its first packet (kEmptyLeaf for an empty leaf): a leaf visit then
// reads one contiguous block, with no dependent load of its count in refs
// or of a per-node packet offset (each a likely cache miss on large scenes).
#ifndef KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
#define KDTREE_CC_KDTREE_LEAF_LAYOUT_H_

#include <cstddef>
#include <cstdint>

#include "cc/geometry/vec3.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr int kPacketLanes = 4;
inline constexpr int kPacketIds = 9 * kPacketLanes;  // where the indices start
inline constexpr int kPacketFloats = kPacketIds + kPacketLanes;
inline constexpr uint32_t kPadLane = 0xFFFFFFFFu;
inline constexpr uint32_t kLastPacket = 0x80000000u;  // on lane 0's index
inline constexpr uint32_t kEmptyLeaf = KdNode::kMaxIndex;  // leaf_nodes index

// Fills tree->leaf_soa and tree->leaf_nodes from the nodes, refs and verts
// (replacing any previous layout). A tree without verts, or with 2^30 - 1
// packets or more, gets none. `parallel`: chunks of nodes run as oneTBB tasks
// (in the caller's task arena); the layout is the same either way.
void LayoutLeafTriangles(KdTree* tree, bool parallel = false);

// Frees the layout: the traversal then reads the vertices by index (the
// kd_index variant of render_bench, and tests comparing the two paths).
void DropLeafLayout(KdTree* tree);

// Whether `tree` has a complete layout (the traversal uses it then).
inline bool HasLeafLayout(const KdTree& tree) {
  return !tree.leaf_nodes.empty() && tree.leaf_nodes.size() == tree.nodes.size();
}

// The vertices of lane l of the packet at `packet` (a, b, c: the soup's
// floats, for IntersectTriangleWatertight).
inline void PacketTriangle(const float* packet, int l, Vec3* a, Vec3* b, Vec3* c) {
  const float* q = packet + l;
  *a = Vec3(q[0 * kPacketLanes], q[1 * kPacketLanes], q[2 * kPacketLanes]);
  *b = Vec3(q[3 * kPacketLanes], q[4 * kPacketLanes], q[5 * kPacketLanes]);
  *c = Vec3(q[6 * kPacketLanes], q[7 * kPacketLanes], q[8 * kPacketLanes]);
}

// Bytes held by the layout (0 when absent).
inline size_t LeafLayoutBytes(const KdTree& tree) {
  return tree.leaf_soa.size() * sizeof(float) + tree.leaf_nodes.size() * sizeof(KdNode);
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
