// Ray-by-ray comparison of two tracers on recorded rays (e.g. the kd-tree's
// render traced again by Embree).
//
// A ray disagrees when the two tracers differ on hit / miss (closest hit for
// primary rays, occlusion for shadow and AO rays), or, for primary rays that
// both hit, when the distances differ by more than 1e-4 relative
// (|t_a - t_b| > 1e-4 max(t_a, t_b)). The triangles the two tracers report on
// that ray (their closest hits, recomputed with Intersect also for shadow and
// AO rays) are then checked in exact arithmetic (exact_check.h), and the ray
// is classified:
//   grazing  the ray's line passes within kGrazingUlps = 4 ulps of an edge of
//            one of those triangles: distance between the ray's line and the
//            edge's line <= 4 FloatUlp(M), M the largest |coordinate| of the
//            ray origin and the triangle's vertices. Translating the vertices
//            to the origin already rounds by up to half an ulp of M, and each
//            test's own arithmetic adds a few more, so two correct float
//            tracers may legitimately differ there.
//   at_origin not grazing; the ray origin lies within kAtOriginUlps = 8 ulps
//            of M of the plane of one of those triangles (distance across the
//            plane), so the sign of t on that triangle is within float
//            rounding: a ray just spawned from a surface, meeting a
//            neighbouring triangle whose plane passes through its origin's
//            rounding box. (8, not 4: the rounding of t grows with the
//            distance of the vertices from the origin, and for long sliver
//            triangles those are all of M; the Embree self-hits seen on
//            stk-ravenbridge-mansion lie at 2.8 to 4.8 ulps.)
//   t_guard  neither; a triangle exactly hit in the ray's t range that
//            the reference missed, and that the watertight test
//            (cc/geometry/watertight.h) rejects on its own: only its
//            conservative "t above its rounding bound" rule (PBRT 3rd ed.
//            3.9.6) does that, for a hit very close to the origin of a ray
//            whose triangle spans the origin's depth.
//   other    everything else (to be looked at).
// Each disagreement also gets an exact verdict, as far as the two reported
// triangles go: the tracer claiming the nearer hit (or any hit, against a
// miss) is right when that triangle is exactly hit, else the other is.
#ifndef KDTREE_CC_RENDER_COMPARE_H_
#define KDTREE_CC_RENDER_COMPARE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "cc/geometry/triangle.h"
#include "cc/render/ray_record.h"
#include "cc/render/tracer.h"
#include "nlohmann/json.hpp"

namespace kdtree {

inline constexpr float kCompareRelT = 1e-4f;
inline constexpr double kGrazingUlps = 4.0;
inline constexpr double kAtOriginUlps = 8.0;

struct KindDisagreements {
  uint64_t rays = 0;
  uint64_t hit_miss = 0;   // one hits (or is occluded), the other not
  uint64_t t_differs = 0;  // primary, both hit, t beyond 1e-4 relative
  uint64_t grazing = 0;    // of hit_miss + t_differs: passes within 4 ulps of an edge
  uint64_t at_origin = 0;  // of the rest: origin within 8 ulps of a reported triangle's plane
  uint64_t t_guard = 0;    // of the rest: an exact hit rejected by the watertight t bound
  uint64_t reference_wrong = 0;  // exact verdict: the reference tracer is wrong
  uint64_t other_wrong = 0;      // exact verdict: the other tracer is wrong
  uint64_t total() const { return hit_miss + t_differs; }
  uint64_t other() const { return total() - grazing - at_origin - t_guard; }
};

struct Disagreements {
  KindDisagreements by_kind[kNumRayKinds];
  KindDisagreements all;
  // Up to 20 examples of non-grazing disagreements (record index and values).
  std::vector<std::string> examples;
  // One JSON object: {"rays", "total", "grazing", "at_origin", "t_guard", "other",
  // "hit_miss", "t_differs", "reference_wrong", "other_wrong",
  // "primary": {...}, "shadow": {...}, "ao": {...}}, in this order.
  nlohmann::ordered_json ToJson() const;
};

// Compares the recorded results of `reference` (whose results `records` hold)
// with `other`, tracing every record again with `other`. `reference` is only
// used to classify disagreeing rays; `soup` is the triangles both were built
// on.
Disagreements CompareTracers(const std::vector<RayRecord>& records, const TriangleSoup& soup,
                             const Tracer& reference, const Tracer& other);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_COMPARE_H_
