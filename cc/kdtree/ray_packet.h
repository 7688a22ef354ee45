// Packets of up to 4 rays traced through the kd-tree together (SSE, one ray
// per lane).
//
// Wald, Slusallek, Benthin & Wagner, "Interactive rendering with coherent ray
// tracing", CGF 20(3), 2001, and Wald's thesis ("Realtime Ray Tracing and
// Interactive Global Illumination", Saarland University, 2004, section 7.2):
// rays whose directions have the same sign on every axis agree on which child
// of any node is the near one, so they can descend together. Each lane keeps
// its own interval; at an inner node the packet goes to one child when every
// active lane needs only that one, else it pushes the far child with the lanes
// that need it and goes on to the near child with the lanes that need that.
// Nodes, leaves and leaf packets are loaded once for the 4 rays.
//
// Exactness: every lane applies the single-ray traversal's rules
// (traversal.h), with the same float operations, to the same intervals, in
// the same front-to-back order, and drops a popped node when its own best hit
// rules it out. So each lane visits exactly the nodes the single-ray
// traversal visits for its ray and tests the same triangles in the same order:
// the results are bit for bit those of Intersect / Occluded (ray_packet_test.cc
// checks this, and brute force, on random, coherent and adversarial packets).
//
// Falls back to one ray at a time when the packet path does not apply: a tree
// without the leaf layout (leaf_layout.h), the fast intersection mode,
// mailboxing, or rays whose direction signs differ on some axis.
#ifndef KDTREE_CC_KDTREE_RAY_PACKET_H_
#define KDTREE_CC_KDTREE_RAY_PACKET_H_

#include "cc/geometry/ray.h"
#include "cc/kdtree/traversal.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr int kRayPacketSize = 4;

// hits[i] = Intersect(tree, rays[i], options) for i < n, 0 <= n <= 4.
void IntersectPacket(const KdTree& tree, const Ray* rays, int n, Hit* hits,
                     const TraversalOptions& options = TraversalOptions());
// occluded[i] = Occluded(tree, rays[i], options) for i < n, 0 <= n <= 4;
// with origin_tris (else null), ray i's options.origin_tri is origin_tris[i]:
// each ray leaves its origin triangle untested (TraversalOptions::origin_tri;
// the renderer's shadow and AO rays, cc/geometry/spawn.h), and
// options.origin_tri must be kNoHit.
void OccludedPacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origin_tris,
                    bool* occluded, const TraversalOptions& options = TraversalOptions());

// Whether IntersectPacket / OccludedPacket take the packet path for these rays
// (else they trace them one by one). For tests and benchmarks.
bool PacketPathApplies(const KdTree& tree, const Ray* rays, int n,
                       const TraversalOptions& options = TraversalOptions());

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RAY_PACKET_H_
