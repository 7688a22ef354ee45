// Packets of up to 16 rays traced through the kd-tree together, one ray per
// vector lane (the renderer's 4x4 pixel blocks and their shadow rays).
//
// Wald, Slusallek, Benthin & Wagner, "Interactive rendering with coherent ray
// tracing", CGF 20(3), 2001, and Wald's thesis ("Realtime Ray Tracing and
// Interactive Global Illumination", Saarland University, 2004, section 7.2):
// rays whose directions have the same sign on every axis agree on which child
// of any node is the near one, so they can descend together. Each lane keeps
// its own interval; at an inner node the packet goes to one child when every
// active lane needs only that one, else it pushes the far child with the lanes
// that need it and goes on to the near child with the lanes that need that.
// Nodes, leaves and leaf triangles are loaded once for all lanes, and each
// triangle is tested against all lanes at once.
//
// The packet's rays are traced in groups that share their direction signs and
// their watertight axes (usually one group). The kernel is 4, 8 or 16 lanes
// wide (SSE4, AVX2, AVX-512; also SSSE3 and Highway's scalar emulation, which
// the tests run too), chosen at run time for the CPU by Google Highway's
// dynamic dispatch (ray_packet_kernel.cc); a group wider than a vector runs
// as several vectors that descend together, a node decided once for all.
//
// Exactness: every lane applies the single-ray traversal's rules
// (traversal.h), with the same float operations, to the same intervals, in
// the same order (front to back, or for any hit with
// TraversalOptions::from_end from the rays' ends), and drops a popped node when its own best hit
// rules it out. So each lane visits exactly the nodes the single-ray
// traversal visits for its ray and tests the same triangles with the same
// test: the results are bit for bit those of Intersect / Occluded
// (ray_packet_test.cc checks this, and brute force, on random, coherent and
// adversarial packets, on every kernel width the machine runs).
//
// Falls back to one ray at a time when the packet path does not apply: the
// fast intersection mode, or an empty tree.
#ifndef KDTREE_CC_KDTREE_RAY_PACKET_H_
#define KDTREE_CC_KDTREE_RAY_PACKET_H_

#include <string>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/kdtree/traversal.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr int kRayPacketSize = 16;

// What the packet traversal did (the counting pass's packet statistics).
// `lanes` counts per ray what TraversalCounters counts for a single ray, so
// for the same rays and options its rays, inner and leaf visits equal the
// single-ray traversal's, and for closest-hit queries its triangle tests too
// (ray_packet_test checks this: each lane visits the nodes its ray's
// traversal visits). The rest is the kernel's own work: a group's lanes
// descend together, so an inner or leaf step is one node for all of them,
// and a triangle step is one vector (its lanes per step:
// lanes.inner_visits / inner_steps, ...).
struct PacketCounters {
  TraversalCounters lanes;
  uint64_t packets = 0;         // calls with at least one ray reaching the tree
  uint64_t groups = 0;          // groups of lanes with the same signs and axes
  uint64_t inner_steps = 0;     // inner nodes visited
  uint64_t leaf_steps = 0;      // leaves reached, empty ones too
  uint64_t pushes = 0;          // children put on the stack
  uint64_t triangle_steps = 0;  // vector tests: a triangle against the lanes,
                                // or a leaf packet against a few rays
};

// hits[i] = Intersect(tree, rays[i], options) for i < n, 0 <= n <= kRayPacketSize;
// `counters` (may be null) gathers what the traversal did.
void IntersectPacket(const KdTree& tree, const Ray* rays, int n, Hit* hits,
                     const TraversalOptions& options = TraversalOptions(),
                     PacketCounters* counters = nullptr);
// occluded[i] = Occluded(tree, rays[i], options) for i < n, 0 <= n <= kRayPacketSize;
// with origin_tris (else null), ray i's options.origin_tri is origin_tris[i]:
// each ray leaves its origin triangle untested (TraversalOptions::origin_tri;
// the renderer's shadow and AO rays, cc/geometry/spawn.h), and
// options.origin_tri must be kNoHit.
void OccludedPacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origin_tris,
                    bool* occluded, const TraversalOptions& options = TraversalOptions(),
                    PacketCounters* counters = nullptr);

// Whether IntersectPacket / OccludedPacket take the packet path with this
// tree and these options (else they trace the rays one by one).
bool PacketPathApplies(const KdTree& tree, const TraversalOptions& options = TraversalOptions());

// The Highway target the packet kernel runs on ("AVX3", "AVX2", "SSE4", ...;
// kdrt's record fast_render.packet_kernel).
const char* PacketKernelTarget();

// The targets this machine can run the kernel on, best first ("AVX3_DL",
// "AVX3", "AVX2", "SSE4", "SSSE3", "SCALAR" on AVX-512 hardware).
std::vector<std::string> PacketKernelTargets();

// While alive, the packet kernel (and every other Highway dispatch of the
// process) runs on the target named `name`, one of PacketKernelTargets():
// for benchmarks and tests that compare the widths on the same rays. ok() is
// false for a name this machine cannot run (nothing changes then). Not
// thread-safe: Highway's choice is process-wide.
class ScopedPacketKernelTarget {
 public:
  explicit ScopedPacketKernelTarget(const std::string& name);
  ~ScopedPacketKernelTarget();
  ScopedPacketKernelTarget(const ScopedPacketKernelTarget&) = delete;
  ScopedPacketKernelTarget& operator=(const ScopedPacketKernelTarget&) = delete;
  bool ok() const { return ok_; }

 private:
  bool ok_ = false;
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RAY_PACKET_H_
