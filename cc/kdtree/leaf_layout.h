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
// The data are the triangles' vertices exactly as in the soup, because the
// watertight test (cc/geometry/watertight.h) must see the very floats of the
// shared vertices: a precomputed edge form (v0 + e1, or Woop's unit-triangle
// transform) would round differently and change the answers. So the results
// are those of the scalar test on the soup's triangles.
//
// Packet layout (40 words): [vertex v][axis k][lane l] at (3 v + k) * 4 + l,
// v = 0, 1, 2 for a, b, c (36 floats), then the 4 lanes' triangle indices
// (uint32 bit patterns, read with memcpy or SSE integer loads). A leaf's
// packets are consecutive; lane 0's index has bit 31 set in the leaf's last
// packet; lanes past a leaf's count hold index kPadLane and zero vertices
// (the traversal masks them). Packet j of a leaf, lane l, is triangle
// 4 j + l of the leaf's list in the builders' ListTree (list_tree.h).
//
// These packets are all the finished tree keeps of its triangles
// (KdTree::leaf_soa; a triangle in several leaves is stored in each): a
// leaf's index in KdTree::nodes is its first packet (kEmptyLeaf for an empty
// leaf), so a leaf visit reads one contiguous block, with no dependent load
// of a count, a list or a vertex by index (each a likely cache miss on large
// scenes). Before 4c5d23d the tree also kept the
// report's lists (4 bytes a reference), a vertex array by index (36 bytes a
// triangle) and a second node array; they served only a slower traversal
// path, and the builder now frees the lists once the packets are written.
#ifndef KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
#define KDTREE_CC_KDTREE_LEAF_LAYOUT_H_

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cc/geometry/vec3.h"
#include "cc/kdtree/list_tree.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr int kPacketLanes = 4;
inline constexpr int kPacketIds = 9 * kPacketLanes;  // where the indices start
inline constexpr int kPacketFloats = kPacketIds + kPacketLanes;
inline constexpr uint32_t kPadLane = 0xFFFFFFFFu;
inline constexpr uint32_t kLastPacket = 0x80000000u;  // on lane 0's index
inline constexpr uint32_t kEmptyLeaf = KdNode::kMaxIndex;  // an empty leaf's index

// Fills out->nodes and out->leaf_soa from the lists' nodes and leaf lists
// and the soup's vertices (`verts`, 3 per triangle), replacing them. False,
// with out->nodes and out->leaf_soa empty, when the tree would need 2^30 - 1
// packets or more. `parallel`: chunks of nodes run as oneTBB tasks (in the
// caller's task arena); the layout is the same either way.
bool LayoutLeafTriangles(const ListTree& lists, const Vec3* verts, bool parallel, KdTree* out);

// Writes the packets of one leaf of `count` > 0 triangles, `ids` into the
// soup's vertices (3 per triangle, `verts`), at `out` (PacketsOf(count)
// packets): the hierarchy over whole triangles (triangle_bvh.h), which
// holds no list tree.
void WriteLeafPackets(const Vec3* verts, const uint32_t* ids, size_t count, float* out);

// The same with the k-th triangle's vertices at rows[9 k .. 9 k + 8] (a, b,
// c): packets regrouped from other packets (leaf_bvh.cc), with no soup.
void WriteLeafPacketsFromRows(const float* rows, const uint32_t* ids, size_t count, float* out);

// Calls f(const float* packet, int lane, uint32_t triangle) for each
// triangle of the leaf whose first packet is at `first`, in packet order.
template <class F>
void ForEachPacketLane(const float* first, const F& f) {
  for (const float* packet = first;; packet += kPacketFloats) {
    uint32_t id[kPacketLanes];
    std::memcpy(id, packet + kPacketIds, sizeof(id));
    const bool last = (id[0] & kLastPacket) != 0;
    id[0] &= ~kLastPacket;
    for (int l = 0; l < kPacketLanes; ++l) {
      if (id[l] != kPadLane) f(packet, l, id[l]);  // pads only follow a leaf's last triangle
    }
    if (last) return;
  }
}

// The triangles of leaf `leaf` of `tree`, in list order, and their number.
std::vector<uint32_t> LeafTriangles(const KdTree& tree, const KdNode& leaf);
uint32_t LeafTriangleCount(const KdTree& tree, const KdNode& leaf);

// The vertices of lane l of the packet at `packet` (a, b, c: the soup's
// floats, for IntersectTriangleWatertight).
inline void PacketTriangle(const float* packet, int l, Vec3* a, Vec3* b, Vec3* c) {
  const float* q = packet + l;
  *a = Vec3(q[0 * kPacketLanes], q[1 * kPacketLanes], q[2 * kPacketLanes]);
  *b = Vec3(q[3 * kPacketLanes], q[4 * kPacketLanes], q[5 * kPacketLanes]);
  *c = Vec3(q[6 * kPacketLanes], q[7 * kPacketLanes], q[8 * kPacketLanes]);
}

// Bytes held by the packets.
inline size_t LeafLayoutBytes(const KdTree& tree) { return tree.leaf_soa.size() * sizeof(float); }

// Bytes held by the finished tree: its nodes and its packets (TreeStats and
// render_bench's records).
inline size_t TreeBytes(const KdTree& tree) {
  return tree.nodes.size() * sizeof(KdNode) + LeafLayoutBytes(tree);
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LEAF_LAYOUT_H_
