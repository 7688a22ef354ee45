// The kd-tree's leaves under a wide bounding-volume hierarchy: the same
// leaves and triangles, reached by box tests instead of split planes.
//
// Why. Traced one class of rays at a time (render_bench --classes), a camera
// ray that crosses the kd-tree's box and hits nothing costs about twice what
// it costs Embree's BVH, and on the hairballs every class of ray loses by
// 0.44-0.66: a ray walks 20-70 split planes through dense geometry, where a
// BVH tests a few wide nodes. This structure keeps what the kd-tree built
// (its partition, its leaves and their triangles) and replaces the walk: each
// node holds up to eight children, each child the box of the geometry under
// a kd subtree or a leaf's group (below), collapsed from the
// kd-tree's own hierarchy (a kd node's children are expanded, the one with
// the largest surface area first, until eight are reached or only leaves
// remain; Wald, Benthin & Boulos, "Getting rid of packets", RT 2008, and
// Wald et al., "Embree", ACM TOG 33(4), 2014, for eight-wide nodes tested in
// one vector). A leaf's box is the union of its triangles' boxes each
// clipped to the leaf's cell, so the boxes of different kd leaves do not
// overlap (they may touch), as the cells do not; a bounded kd-tree in the
// sense of Woop, Marmitt & Slusallek ("B-KD trees for hardware accelerated
// ray tracing of dynamic scenes", Graphics Hardware 2006), but wide.
//
// Flat groups (ours; since 2026-12-07, session 47). Each kd leaf becomes one
// BVH leaf per group of its triangles: per axis-aligned plane, the triangles
// whose three vertices lie on it, and then the triangles flat on no such
// plane; each group's box its triangles' boxes clipped to the cell, its
// triangles in packets of their own (padded to whole packets of four), which
// the BVH holds (LeafBvh::leaves) and reads instead of the tree's. A flat
// group's box is flat: a shadow ray leaving that plane (its origin is offset
// past it: spawn.h) does not enter it, where it entered the kd leaf's box,
// which holds the leaf's other geometry too (on morse-indoor that leaf took
// 3.7 of a shadow ray's 5.2 triangle tests). Measured before it was built in
// (a scratch build: the grouped BVH as a second tracer of the same tree,
// render_bench --envs, 5 paired rounds, one process, all 25 standard scenes
// of 50,000 triangles or more): kd_bvh_packet's renders took 0.960-1.009 of
// the time of the BVH over whole kd leaves (median 0.989; lost-empire 0.960,
// morse-kitchen 0.969, 8 scenes below 0.98, the worst morse-trees 1.009),
// where the same tree twice gave 0.972-1.007 (median 0.999). Groups only of
// at least m triangles a plane (the others with the rest) gained less: m = 2,
// 0.972-1.000 on lost-empire, morse-kitchen, city2 and morse-indoor and 0.986
// on city; m = 4, lost-empire alone (0.976). The packets are 0-21 % larger
// than the tree's on 23 of the 25 scenes, 80 % on city and city2 (groups of
// one or two triangles).
//
// Exactness (traversal in leaf_bvh_traversal.cc). The closest hit's point p
// on triangle T lies in the closed cell of some leaf that references T (the
// builders keep a triangle in every leaf whose closed cell its surface meets,
// which the kd-tree's own traversal relies on), and the box of T's group in
// that leaf contains T's part in that cell, since a box of T clipped to the
// cell contains it (min and max are exact). The box test is conservative
// (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013: the slab distances are
// within gamma(3) of the exact ones, and the interval is widened by 4 u on
// each side), and a box is
// passed over only when it starts beyond the best hit by more than the
// kd-tree's slack, so every leaf holding the closest hit or a tie is tested,
// with the kd-tree's leaf step (leaf_step-inl.h): the answers are the
// kd-tree's, bit for bit (leaf_bvh_test.cc, the adversarial suite's
// preset_check.cc).
//
// Memory (render_bench's records, the 25 standard scenes of 50k triangles or
// more, 44ba8fc): 256 bytes a node, 4.4 to 15.6 bytes a triangle (bvh_bytes),
// 39 on city and city2, whose groups hold one or two triangles; and its own
// leaf packets (bvh_packet_bytes), 53 to 149 bytes a triangle: against the
// tree's bytes (its nodes and packets), 2-4 % fewer on the meshes, up to 16 %
// more elsewhere, 74 % more on city and city2.
// Its build from the tree took 0.01-0.08 s below 300k triangles and 0.43-0.80
// s on the scenes of 1-1.5M (0.06-0.23 s before the groups), most of it the
// kernel's first touch of its packets' fresh pages (courtyard-1m, perf).
// With the groups, a camera packet on lost-empire takes 10.1 triangle steps
// (22.0 before), on city2 2.4 (9.6), a shadow packet on morse-indoor 2.2
// (5.5); render_bench's packet_counts, out/sweep_s47.
//
// Measured (render_bench --classes, sah-packet, 25 standard scenes, two
// processes of 5 paired rounds, 2026-12-06; README, "What the reproduction
// found"): single rays 0.81-0.96 of Embree's speed (median 0.88), where the
// kd-tree's own traversal gives 0.60-0.99 (0.85); render time 0.72-0.76 of
// kd_origin's on the hairballs, up to 1.05 elsewhere.
//
// Tried and not kept (render_bench, sah-packet, one process, the variant
// on a second copy of the tree or of the code, 5 paired rounds, on bunny,
// city2, lost-empire, hairball-small, courtyard-1m and teapots unless said;
// 2026-12-06):
//  - boxes padded by 2^-20 of the scene's reach (not needed: the boxes are
//    exact), in a first version: on lost-empire its shadow rays took 1.75
//    times as long as this version's (render_bench --classes, paired with
//    Embree's, two processes each), as a ray leaving a flat surface entered
//    the padded flat boxes beside it;
//  - nodes of four children (SSE, 128 bytes): renders 1.10-1.17 times as
//    long;
//  - a leaf's packets as leaves of their own, each with its box: 0.99-1.19
//    (bunny, teapots, city2); for the packets (kd_bvh_packet, a second tree
//    through --envs, 7 paired rounds, bunny, city2, courtyard-1m,
//    hairball-small, hairball-1m, lost-empire, morse-indoor; 2026-12-07),
//    a leaf of more than one packet (or three) under a node of its
//    packets, each box its triangles' boxes clipped to the cell: renders
//    1.00-1.19 times as long (4 times the nodes), and with the leaf's
//    triangles first ordered by a median split of their centroids, so
//    that a packet's four lie together, 1.00-1.19 too: the triangles of a
//    kd leaf cross one small cell, so any four of them cover most of it
//    and their box culls few lanes, while each added node costs a step;
//  - the kd-tree's front-to-back order stored per node and direction octant
//    (a permutation of the slots), the hit children compressed onto the
//    stack in that order, without a branch or a sort: renders 1.04-1.06
//    times as long, passes up to 1.14: the permute and the compress lengthen
//    every node's dependent chain;
//  - any-hit children in slot order instead of farthest first: shadow pass
//    0.96-1.03;
//  - prefetching the children pushed on the stack: within 2 %;
//  - a tree tuned for this traversal: sah-packet's K_T (45, tuned for the
//    kd-tree's walk) lowered to 20 or 30 (render_bench --envs with
//    --env_variant kd_bvh, 5 paired rounds, 8 scenes): renders 0.977-1.048
//    and 0.971-1.017 times as long as K_T 45's, the same tree twice
//    0.995-1.011; traced as kd_bvh_packet (six scenes, 7 paired rounds),
//    K_T 20 0.973-1.122, 30 0.984-1.051, 60 0.990-1.031 and 90
//    0.984-1.078, the same tree twice 1.001-1.010;
//  - a tree with the per-triangle leaf cost (sahPacket 1) instead of
//    per packet of four, K_T 20, 45 or 80, traced as kd_bvh_packet
//    (--envs, 5 paired rounds, the seven scenes above; 2026-12-07): renders
//    0.98-1.42, 0.99-1.15 and 0.97-1.05 times as long as sah-packet's;
//  - leaves without most duplicates: a triangle whose box reaches past the
//    cell of its vertices' centroid by at most r of the cell's extent on
//    every axis kept once, whole, in that leaf (its box grown to hold it),
//    the others in every leaf as here (exact as here: the owner's box holds
//    the triangle); the same kernels, render_bench in one process per r
//    (the variant beside kd_bvh_packet, 5 paired rounds; bunny, city2,
//    lost-empire, morse-indoor, teapots, courtyard-1m; 2026-12-07).
//    kd_bvh_packet's time over the variant's: r = 0.25, bunny 1.08 and
//    0.98-1.005 elsewhere; r = 1, bunny 1.08, teapots 1.04, city2 0.91;
//    every triangle owned, bunny 1.06, teapots 1.08, city2 0.85,
//    courtyard-1m 0.94; r = 0 (almost nothing owned; the control)
//    0.98-1.02. Camera packets' triangle steps fell from 22.4 to 16.3 on
//    bunny and rose from 9.6 to 21.9 on city2 (its large triangles' whole
//    boxes overlap), and stayed within 10 % elsewhere: the kd leaves hold
//    many triangles in a small cell whether or not they are duplicates, so
//    what the BVH of whole triangles (triangle_bvh.h) gains is its
//    partition more than the single reference.
//
// The packet kernel (leaf_bvh_packet_kernel.cc), tried and not kept
// (render_bench, sah-packet, the variant on a second copy of the tree, one
// process, 5 paired rounds, bunny, city2, lost-empire, hairball-small,
// teapots, courtyard-1m; 2026-12-06): one interval-arithmetic test of a node's
// eight boxes for the whole group (Wald et al.'s packet culling: the lanes'
// origins and reciprocals as intervals; exact bounds, as the float operations
// are monotone), every child that interval enters visited with all the lanes:
// camera pass 1.40-2.96 times as long, shadow pass 1.5-130 times (a shadow
// packet's origins are scattered over the surfaces, so its intervals enter
// nearly every box). The same test as the only one at inner nodes, for camera
// packets (their lanes share an origin, so it is tight: SlotFilter), children
// ordered by its bound, and each lane's test of a leaf's box made when the
// leaf is reached (the lanes then those whose ray enters it before their best
// hit): camera pass 1.021-1.044 times as long, courtyard-1m 1.130, where the
// shadow pass, the same code on both sides, gave 1.005-1.029 (in-process A/B,
// 7 paired rounds, the six scenes): the lanes are no longer narrowed on the
// way down, so each leaf's test and each node's pop serve more of them. A
// single-ray fallback (Benthin et al. 2012; Embree's hybrid traversal): a lane
// left alone at an inner node walks its subtree with the single ray's
// traversal from its best hit so far: camera pass 0.982-1.021, shadow pass
// 0.948-0.996 in a first process (bunny, city2, lost-empire, hairball-small,
// courtyard-1m, hairball-1m) but 0.965-1.021 in a second (the same and
// teapots, rungholt-1m; shadow rays only), up to two lanes no different from
// one: within the noise, so not kept. Embree's hybrid threshold (a shadow
// packet of 16 goes one ray at a time once 14 lanes or fewer are left) in the
// same A/B (city2, morse-indoor, lost-empire, hairball-small, hairball-1m,
// courtyard-1m, bunny; 2026-12-07): with up to 3, 8 or all 16 lanes walking
// alone, the shadow pass took 0.99-1.02, 1.01-1.09 and 1.23-1.86 times as
// long, and 0.92, 0.91 and 0.90 on hairball-1m alone: a lane walking alone
// costs 1.2 to 1.9 times what it costs in the packet. With the walk's
// reciprocals taken from the packet (no division a lane), up to 3 lanes:
// shadow pass 0.99-1.02, hairball-1m 0.94 (T_R 0.98); up to 5: 0.99-1.08,
// hairball-1m 0.93: a gain on one scene against small losses on the others.
// Also not kept (same A/B): the leaf where the thread's last shadow packet
// found an occluder tested first for the lanes entering its box (the issue's
// "last occluder of the neighbouring ray"): shadow pass 0.997-1.048 (fforest
// too), no scene faster; for lanes sharing their origin, the planes' offsets
// from it taken once in scalars (one multiply a lane instead of a subtract and
// a multiply): camera pass 1.008-1.040; and a box per leaf packet (24 bytes)
// against which a leaf's lanes were tested before its four triangles: it
// skipped 28-49 % of the packets and left 4-7 of a packet's 13 lanes, yet
// renders took 1.00-1.13 times as long. Nor a node's one or two children
// ordered without a branch (a select on the lead lane's entry distances, the
// second child always written to the stack and the top raised by count - 1;
// the sort kept for three or more): T_R 0.996-1.017, camera pass 1.000-1.016,
// the control's noise (bunny, city2, hairball-1m, lost-empire, courtyard-1m,
// morse-indoor; 2026-12-07).
//  - At a node where the group's slot filter leaves one candidate slot, an
//    inner node, that child taken with the group's lanes and without their
//    slab test (exact: the child's boxes lie inside its box): T_R 0.997-1.006,
//    camera pass 0.990-1.016 (in-process A/B, the change on AVX3_DL against
//    AVX3, 7 paired rounds; bunny, lost-empire, morse-trees, city2,
//    morse-indoor, hairball-1m, courtyard-1m; 2026-12-07): a node step is not
//    bound by the lanes' test.
//  - Any-hit children in a static order per node by the ray-termination SAH
//    (Ize & Hansen, "RTSAH traversal order for occlusion rays", CGF 30(2),
//    2011, which the issue names for single shadow rays) instead of farthest
//    first: each node's slots sorted by alpha / C, where a leaf's alpha is one
//    less the product over its triangles of (1 - 2 A_t / SA(box)) (Cauchy's
//    formula for random lines), its C its triangles, and a node's alpha and C
//    combine its children's with p = SA(child) / SA(node) and K_T 2; the
//    children then visited in slot order, without a sort. Same A/B, nine
//    scenes (bunny, lost-empire, morse-trees, city2, morse-indoor,
//    hairball-1m, hairball-small, courtyard-1m, dragon), shadow pass: packets
//    0.964 on hairball-1m, 1.014 on city2, 1.029 on courtyard-1m and
//    0.985-1.009 on the others; single rays (kd_bvh) 0.966 on morse-indoor,
//    0.971 on hairball-small, 1.020 on hairball-1m, 1.027 on city2, 1.048 on
//    courtyard-1m and 0.988-1.002 on the others: no consistent gain either
//    way. Farthest first already leaves for last the leaf of the ray's own
//    surface, which rarely stops it.
//  - Mailboxing (a lane's test of a triangle skipped when the same group has
//    already tested it for that lane in another leaf; exact, as the test is
//    deterministic and a lane's best t only falls): measured only, with
//    counters in one render (kd_bvh_packet, camera and shadow rays;
//    2026-12-07). Such repeated lane tests were 7.0 % of the lane tests on
//    bunny, 4.5-4.6 % on hairball-1m and courtyard-1m and 1.1-2.9 % on
//    lost-empire, morse-trees and city2; a whole triangle step was a repeat in
//    0.5-2.8 % of the steps: too few to pay for a lookup at every step.
//  - With the flat groups (render_bench --envs, the variant as a second tree,
//    7 paired rounds, one process; city2, bunny, lost-empire, morse-trees,
//    hairball-1m, courtyard-1m, morse-indoor, dragon; 2026-12-07): a
//    hierarchy built anew over the groups by the binned SAH (Wald, RT 2007;
//    as triangle_bvh.h's, a group's cost its packets) instead of the kd
//    hierarchy collapsed, with leaves of one group: renders 0.981-1.030 times
//    as long (lost-empire 0.981, hairball-1m 1.030), and with groups merged
//    into leaves of up to 16 triangles where the SAH prefers it: 0.983-1.021
//    and 0.982-1.034 in two processes; the same tree twice 0.987-1.009. The
//    kd hierarchy is as good a hierarchy over these leaves as the SAH's.
//    And sah-packet's K_T (45) lowered again, now that a leaf's flat
//    triangles are leaves of their own: K_T 20 0.995-1.053, K_T 30
//    0.970-1.026 (bunny 0.970, one process), the same tree twice
//    0.986-1.036.
//    Nor (same A/B; city2, city, lost-empire, morse-indoor, morse-kitchen,
//    rungholt-1m, bunny, courtyard-1m) a plane's flat groups of sibling kd
//    cells merged into one BVH leaf, going up the kd hierarchy while the
//    merged group holds at most 4, 8 or 16 triangles (a large flat triangle
//    is a leaf in every cell it crosses): renders 0.987-1.019 times as long,
//    the shadow pass on city and city2 0.965-0.982; the same tree twice
//    0.988-1.019 (shadow pass on city and city2 1.010): a per cent at most.
#ifndef KDTREE_CC_KDTREE_LEAF_BVH_H_
#define KDTREE_CC_KDTREE_LEAF_BVH_H_

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/geometry/ray.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

struct PacketCounters;  // ray_packet.h

inline constexpr int kBvhWidth = 8;

struct alignas(64) LeafBvhNode {
  static constexpr uint32_t kLeafBit = 0x80000000u;  // child: a leaf's first packet
  static constexpr uint32_t kNone = 0xFFFFFFFFu;     // an unused slot (its box is empty)
  // Per slot: the box's lo x, y, z, then hi x, y, z; an unused slot's box is
  // lo = +inf, hi = -inf, which no ray enters.
  float box[6][kBvhWidth];
  // Per slot: a node's index, kLeafBit | the leaf's first packet in
  // KdTree::leaf_soa, or kNone.
  uint32_t child[kBvhWidth];
  // Per slot holding a leaf: its number of packets, up to 255 (0 for other
  // slots), for the packet kernel's prefetch; in the node's padding (it
  // stays 256 bytes).
  uint8_t packets[kBvhWidth];
};
static_assert(sizeof(LeafBvhNode) == 256, "four cache lines a node");

// The hierarchy with the leaf packets it reaches: all its traversals read.
struct LeafBvh {
  // nodes[0] is the root; empty when there is no triangle to reach.
  std::vector<LeafBvhNode> nodes;
  // What the traversals read of a tree, and nothing else: `leaves.leaf_soa`
  // holds each BVH leaf's triangles in packets (leaf_layout.h; a leaf's
  // packets end with kLastPacket), `leaves.bounds` the scene's box,
  // `leaves.triangles` the soup's triangle count; `leaves.nodes` is empty.
  KdTree leaves;
  size_t node_bytes() const { return nodes.size() * sizeof(LeafBvhNode); }
  size_t packet_bytes() const { return leaves.leaf_soa.size() * sizeof(float); }
  size_t bytes() const { return node_bytes() + packet_bytes(); }
};

// The hierarchy over `tree`'s non-empty leaves, each split into its flat
// groups and the rest (above), with their packets copied from the tree's:
// it does not refer to `tree`. Its packets are counted first (one pass over
// the leaves, LeafBvhPacketBytes) and allocated once: ResourceExhausted,
// before any allocation, when they need more than max_packet_bytes (the
// message ends with how_to_raise in parentheses, as CheckMemoryBudget's) or
// more packets than a node's slot can address (2^31).
absl::StatusOr<LeafBvh> BuildLeafBvh(
    const KdTree& tree, uint64_t max_packet_bytes = std::numeric_limits<uint64_t>::max(),
    const std::string& how_to_raise = "BuildLeafBvh's max_packet_bytes");

// At least the bytes of BuildLeafBvh(tree)'s packets (LeafBvh::packet_bytes;
// equal unless a group meets its cell nowhere), counted without building it.
uint64_t LeafBvhPacketBytes(const KdTree& tree);

// The kd-tree's queries (traversal.h, watertight test), through `bvh`:
// Intersect's closest hit, bit for bit, and whether any triangle but
// origin_tri (kNoHit: none) is hit (Occluded with that origin triangle).
// Children are visited nearest first for the closest hit and farthest first
// for any hit (the kd-tree's from_end order: a shadow ray searched from the
// light).
Hit IntersectLeafBvh(const LeafBvh& bvh, const Ray& ray);
bool OccludedLeafBvh(const LeafBvh& bvh, const Ray& ray, uint32_t origin_tri = kNoHit);

// The same for packets of n <= 16 rays, one ray per vector lane
// (leaf_bvh_packet_kernel.cc): each ray's answer is the single ray's, bit
// for bit. origin_tris may be null (no ray has one). `counters` (may be
// null) gathers what the kernel did, as the kd-tree's packet kernel counts
// it (ray_packet.h), its inner steps the BVH's nodes.
void IntersectPacketLeafBvh(const LeafBvh& bvh, const Ray* rays, int n, Hit* hits,
                            PacketCounters* counters = nullptr);
void OccludedPacketLeafBvh(const LeafBvh& bvh, const Ray* rays, int n,
                           const uint32_t* origin_tris, bool* occluded,
                           PacketCounters* counters = nullptr);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LEAF_BVH_H_
