// Stack-based kd-tree traversal: closest hit and any hit.
//
// Hapala & Havran, "Review: Kd-tree traversal algorithms for ray tracing", CGF
// 30(1), 2011 (the report's [1]), the variant the report uses: the near child
// is the left one when the ray's direction on the split axis is positive (its
// sign bit clear, so -0 counts as negative and +0 as positive), the right one
// otherwise. With t_split the distance to the plane and [t_entry, t_exit] the
// ray's interval in the node:
//   t_split > t_exit + tol      -> near child only
//   t_split < t_entry - tol     -> far child only
//   otherwise                   -> near child on [t_entry, t_split + tol], the
//                                  far child on [t_split - tol, t_exit] pushed
//                                  on a stack (t_split clamped to the interval).
// (Any-hit queries may take the two children the other way round, from the
// ray's end: TraversalOptions::from_end.)
// A leaf's triangles are tested against the best hit so far; a hit beyond the
// leaf is kept as the best so far and only confirmed once no node that could
// hold a nearer one is left.
//
// Robustness (the hard cases of the adversarial suite, cc/robust/):
//  - Every plane is treated as delta thick, delta = 16 * 2^-24 * (the largest
//    coordinate difference between the ray origin and the scene box): a
//    triangle test may accept a point a few ulps of that distance outside the
//    triangle (Moeller-Trumbore does), and the leaf holding such a hit must
//    still be visited. In t this is tol = delta / |dir[axis]|, which also
//    covers the rounding of t_split.
//  - Shadow rays (any hit from the end) with the watertight test use a
//    tolerance relative to the node's interval instead (ray_setup.h
//    IntervalTol): 16 u max(|t_entry|, |t_exit|) + 2^-126, u = 2^-24, from
//    the node's interval or an ancestor's. The watertight test decides
//    exactly whether the line meets a triangle (watertight.h: an edge sign
//    within its error bound is computed exactly), so a hit lies on the exact
//    segment and the planes need cover only the traversal's own rounding:
//    t_split = fl(fl(split - o) * fl(1 / d)) is within 3 u |t| of the true
//    crossing, and each stored bound rounds once more (u), so the decision is
//    right whenever |t_split| <= 2 max(|t_entry|, |t_exit|); beyond, the
//    crossing is far outside the interval. Near the ray's origin this is far
//    thinner than tol, so a shadow ray leaving a surface that lies in a split
//    plane no longer visits the cells behind it. Measured (render_bench,
//    sah-packet, 2026-12-06): the single-ray shadow pass 7.5 % shorter on
//    rungholt-1m and lost-empire, the packets' 10-12 %, unchanged on six to
//    eight other scenes. The report's traversal and its counting pass (front
//    to back) keep tol. Closest-hit rays (the camera's) could take the same
//    tolerance, but it bought nothing there: camera pass 0.989-1.016 of
//    tol's on five scenes (one process, 7 paired rounds), as camera rays
//    cross split planes far from their origin.
//  - Rays parallel to a split plane (direction +0 or -0 on its axis, 1/d
//    infinite): t_split is +-inf (never 0 * inf: no NaN decides anything); the
//    ray visits the side its origin is on, or both children whole when the
//    origin is within delta of the plane (origins exactly on the plane
//    included, where (split - o) * inf is NaN).
//  - Origins exactly on a split plane with a nonzero direction: t_split = 0,
//    both children are visited from t = 0.
//  - The root interval is padded by 1 + 2 gamma(3) (Ize, "Robust BVH Ray
//    Traversal", JCGT 2(2), 2013) and by delta per slab.
//  - The search ends only when every remaining node starts beyond best.t +
//    slack, slack = 64 * 2^-24 * (the ray's largest depth, in t, of the scene
//    box along its dominant axis): a bound on the rounding of a triangle's t,
//    so a triangle whose computed t ties with or undercuts the best hit is
//    still tested, and the answer is exactly the brute-force one (ties
//    included: Closer()).
//  - Rays are checked by SanitizeRay (cc/geometry/ray_check.h): NaN/Inf
//    components, a zero direction or a NaN interval make a miss.
//
// Intersection mode (cc/geometry/intersection_mode.h): kWatertight (Woop et
// al. 2013, the default) or kFast (Moeller-Trumbore); the traversal, the leaf
// layout and the leaf step are the same, so timing one mode against the other
// times the two tests (cc/robust/robust_cost_bench.cc).
//
// Per-ray counters (N_IT: triangle tests, N_TR: inner nodes visited) and the
// mode are template parameters, so the fast path carries no counting code.
//
// Speed (none of it changes a result):
//  - The per-ray set-up (the ray's check, reciprocals, tolerances, the
//    padded root interval, the watertight ray) runs in SSE, bit-identical to
//    the scalar code (cc/kdtree/ray_setup.h SanitizeAndSetUpRay).
//  - Leaves read their triangles' vertices in leaf order, in packets of 4
//    (KdTree::leaf_soa, cc/kdtree/leaf_layout.h; the builder fills them):
//    one contiguous block per leaf, never a vertex fetched by index.
//  - The common rejection of the watertight test (edge functions of definitely
//    different signs, the same float expressions as watertight.h) runs first,
//    with the packets on 8 triangles at once (two packets, where the build's
//    static target has 256-bit vectors) or 4 (SSE); it also drops triangles
//    whose three vertices lie behind the origin (tmin >= 0), and the rest of
//    the test runs in vectors too, the scalar test only for lanes within
//    rounding of an edge or of tmin (lane_test-inl.h, the packet kernel's
//    code). The fast test runs on the same packets, 8 or 4 triangles at once,
//    bit for bit IntersectTriangle (lane_fast_test-inl.h).
//  - No mailboxing (Amanatides & Woo 1987; Havran's thesis, section 5.5): a
//    per-ray table of tested triangles was an option here until the plain
//    traversal's render time over its own measured 0.96-1.03 on the 25
//    scenes of 50k triangles or more of the standard profile
//    (experiments/bench.py, sah-packet, 5 paired rounds, 2026-12): a vector
//    step tests a leaf packet's triangles at once, so skipping one saves
//    nothing.
//  - Tried and not kept (render_bench, sah-packet, one thread, old and new
//    binaries alternated, 2026-12-06; the same answers each time):
//    - a branch-free inner step (the stack entry always written, the next
//      node and interval chosen by selects): renders 1.6-1.7x as long on
//      bunny and city. The branches are predicted, so the next node's load
//      starts early; a select makes it wait (as in the packet kernel);
//    - four leaf packets a step (16 lanes) where the static target has
//      512-bit vectors: render times within 2 % of two a step on bunny, city,
//      hairball-small and rungholt-1m (one process 4 % slower on the last);
//      on an Ice Lake server, 1.14-1.19 times as long (leaf_step-inl.h);
//    - other tighter tolerances for shadow rays (ray_setup.h);
//    - the near and far child chosen without a branch (an XOR mask from the
//      direction's sign): renders 10-13 % longer on bunny, city2, teapots
//      and rungholt-1m (one process, the old code on a second, identical
//      tree, 7 paired rounds). Predicted, the branch lets the next node's
//      load start before the node's axis and the ray's sign are read;
//    - for shadow rays searched from the end, a prefetch of the pushed near
//      child (as front to back prefetches the far one): shadow pass up to
//      3.7 % shorter on four scenes and 0.6 % longer on rungholt-1m, within
//      twice the control's spread; with the first packet of a pushed leaf
//      prefetched too, 1-3 % longer.
//    - ropes for shadow rays (Havran's thesis, 2000; Popov et al., EG 2007):
//      a leaf record of 64 bytes (its box, six ropes pushed down as far as
//      each face allows, its first packet), the walk from the light's leaf
//      (kept between rays) back to the origin, each exit face found from the
//      leaf's box and every decision taken only clear of rounding (else the
//      stack traversal: 0.01 % of bunny's shadow rays). 0 mismatches against
//      `kd` and brute force (render_bench, 300 rays a scene; all presets on
//      the test scenes). It visits the same leaves (bunny: 5.8 a ray) with
//      15.4 descent steps instead of 27.2 inner steps, yet the shadow pass
//      (with the renderer's own work) took 1.27-1.58 times as long (bunny,
//      city2, lost-empire; one process, 5 paired rounds): each hop waits on
//      the leaf record, the exit face's computation and the rope's node,
//      where a predicted inner step lets the next node's load start at once;
//    - the path to the light's leaf kept between shadow rays and replayed
//      in vectors (every plane's crossing at once, the node-by-node
//      decisions checked against the path, the descent's pushes written;
//      the same nodes and intervals): the light sits in empty space, so the
//      path is short (bunny 7.5 of a ray's 29 inner steps, city2 6.2 of
//      18.9), and the shadow pass took 1.05-1.10 times as long on bunny and
//      city2, 0.99-1.07 on lost-empire (10.4 of 19.9 replayed; one process,
//      5 paired rounds). Front to back, the steps before a shadow ray's
//      first leaf are 9.8-17.3 of 13.1-29.4, and 9.4-16.3 of them are the
//      previous ray's (bunny, city2, lost-empire, teapots, stk-candela-city,
//      courtyard-1m); replaying those would have to beat both the replay's
//      cost above and from-end order's 0-11 %.
//    - for shadow rays, a leaf step skipped when every live triangle lies
//      behind the origin along the ray's dominant axis (the leaf step's own
//      "behind" rejection, tested before the shear): 0.33-0.67 of 2.0-3.2
//      steps a ray on the flat scenes hold nothing else. Shadow pass 1-4 %
//      shorter on stk-candela-city, stk-cocoa-temple, city, city2 and
//      lost-empire, 2.8 % longer on hairball-small (second tree, 7 paired
//      rounds; control 0.989-1.007).
//    - bounds on subtrees (as in Woop, Marmitt & Slusallek's B-KD trees,
//      Graphics Hardware 2006): for inner nodes whose geometry (each leaf
//      triangle's box clipped to its leaf's cell) fills a box of at most a
//      given fraction of the cell's surface area, the ray's interval
//      clipped to that box (the root box's padded clip), the subtree
//      skipped when it is empty. 0 mismatches; slower at every fraction
//      tried (render_bench, --variants kd against the boxes on a second
//      tree, 5-7 paired rounds, bunny, city2, armadillo; at 0.5 also
//      teapots, lost-empire, refined-elephant; 2026-12-06): at 0.2 (16-772
//      nodes with a box) the shadow pass 1.05-1.08 times as long, camera
//      1.03-1.04; at 0.5 (1.4-5 % of the nodes) 1.06-1.10 and 0.99-1.03;
//      at 0.9 (17-27 %) 1.11-1.22 and 1.02-1.12. By class (render_bench
//      --classes), the camera rays that cross the tree's box and hit
//      nothing, which the boxes were for, took 1.00-1.13 times as long:
//      the SAH's empty cuts leave the boxes little to cull, and the check
//      at each node costs every inner step.
#ifndef KDTREE_CC_KDTREE_TRAVERSAL_H_
#define KDTREE_CC_KDTREE_TRAVERSAL_H_

#include <cstdint>

#include "cc/geometry/intersection_mode.h"
#include "cc/geometry/ray.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

struct TraversalCounters {
  uint64_t triangle_tests = 0;  // N_IT summed over rays
  uint64_t inner_visits = 0;    // N_TR summed over rays
  uint64_t leaf_visits = 0;
  uint64_t rays = 0;
  void Add(const TraversalCounters& o) {
    triangle_tests += o.triangle_tests;
    inner_visits += o.inner_visits;
    leaf_visits += o.leaf_visits;
    rays += o.rays;
  }
};

// Options of one query. Defaults: the report's traversal, watertight test.
struct TraversalOptions {
  IntersectionMode mode = IntersectionMode::kWatertight;
  // The triangle a secondary ray leaves from (the renderer's primary hit), or
  // kNoHit. With the watertight test it is not tested: the spawned origin lies
  // strictly on the ray's side of that triangle's exact plane (spawn.h), so
  // the line meets the plane only at t < 0 (or beyond the light, for a light
  // within rounding of the plane), and the watertight test decides t > tmin
  // exactly: it never reports that triangle. Skipping it saves the full test
  // of the one triangle that always passes the 2D edge test (about one per
  // shadow ray). The fast test has no such guarantee: ignored there.
  uint32_t origin_tri = kNoHit;
  // Any hit only (Occluded): where the ray crosses a node's plane, visit the
  // far child first and push the near one, so the segment is searched from
  // its end (tmax) back toward its origin. Off: front to back, as the report
  // traverses every ray. The same nodes are visited with the same intervals
  // and the same triangles tested until a hit, so the answer is the same;
  // only how soon an occluder is found changes. For a shadow ray the end is
  // the light: an occluded ray meets its occluder without first crossing the
  // cluttered cells around the surface it leaves (whose triangles, its own
  // neighbours, rarely occlude it), and an unoccluded one visits every node
  // either way. Ize & Hansen ("RTSAH traversal order for occlusion rays",
  // CGF 30(2), 2011) order occlusion rays by a per-node estimate instead.
  // Measured on sah-packet trees of 6 scenes (render_bench, 7 paired rounds,
  // single shadow rays skipping their origin triangle): this order took the
  // shadow pass 0-11 % less than front to back (T_R paired 1.01-1.05), the
  // larger child by triangle area first 0-3 % more. Front to back with the
  // relative tolerance too (2026-12-06, a second tree, 7 paired rounds):
  // shadow pass 1.00-1.09 times as long on hairball-small, hairball-1m
  // (62 % of its shadow rays occluded), fforest, bunny, city2 and dragon.
  // The renderer's secondary rays take it (KdTreeTracer::Occluded); the
  // counting pass keeps the report's order.
  bool from_end = false;
};

// Deepest stack the traversal needs is the tree depth; Config::Validate caps
// maxDepth at 60.
inline constexpr int kMaxTraversalStack = 64;

// Options with only the triangle test chosen.
inline TraversalOptions WithTest(IntersectionMode mode) {
  TraversalOptions o;
  o.mode = mode;
  return o;
}

// The two queries. Intersect: the closest hit with ray.tmin < t <= ray.tmax
// (ties: the smaller triangle index). Occluded: whether any triangle is hit
// with ray.tmin < t <= ray.tmax (early exit). Default options: the watertight
// test, no origin triangle; `counters` (may be null) gathers
// N_IT and N_TR.
Hit Intersect(const KdTree& tree, const Ray& ray, const TraversalOptions& options = TraversalOptions(),
              TraversalCounters* counters = nullptr);
bool Occluded(const KdTree& tree, const Ray& ray, const TraversalOptions& options = TraversalOptions(),
              TraversalCounters* counters = nullptr);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TRAVERSAL_H_
