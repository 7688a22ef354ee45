// Ray-by-ray comparison of two tracers on recorded rays (e.g. the kd-tree's
// render traced again by Embree).
//
// A ray disagrees when the two tracers differ on hit / miss (closest hit for
// primary rays, occlusion for shadow and AO rays), or, for primary rays that
// both hit, when the distances differ by more than 1e-4 relative
// (|t_a - t_b| > 1e-4 max(t_a, t_b)). Each disagreeing ray is classified:
//   grazing  the closest hit of either tracer on that ray (recomputed with
//            Intersect, also for shadow and AO rays) lies within 1e-5 of a
//            triangle edge in barycentrics: min(u, v, 1 - u - v) < 1e-5. Two
//            watertight-enough tracers legitimately differ there: float
//            rounding decides which side of an edge the ray passes.
//   other    everything else (to be looked at).
// Both kinds of disagreement (hit_miss, t_differs) are also counted, split by
// ray kind.
#ifndef KDTREE_CC_RENDER_COMPARE_H_
#define KDTREE_CC_RENDER_COMPARE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "cc/render/ray_record.h"
#include "cc/render/tracer.h"

namespace kdtree {

inline constexpr float kCompareRelT = 1e-4f;
inline constexpr float kGrazingBary = 1e-5f;

struct KindDisagreements {
  uint64_t rays = 0;
  uint64_t hit_miss = 0;   // one hits (or is occluded), the other not
  uint64_t t_differs = 0;  // primary, both hit, t beyond 1e-4 relative
  uint64_t grazing = 0;    // of hit_miss + t_differs: near an edge
  uint64_t total() const { return hit_miss + t_differs; }
  uint64_t other() const { return total() - grazing; }
};

struct Disagreements {
  KindDisagreements by_kind[kNumRayKinds];
  KindDisagreements all;
  // Up to 20 examples of non-grazing disagreements (record index and values).
  std::vector<std::string> examples;
  // One JSON object: {"total", "grazing", "other", "hit_miss", "t_differs",
  // "primary": {...}, "shadow": {...}, "ao": {...}}.
  std::string ToJson() const;
};

// Compares the recorded results of `reference` (whose results `records` hold)
// with `other`, tracing every record again with `other`. `reference` is only
// used to classify disagreeing rays.
Disagreements CompareTracers(const std::vector<RayRecord>& records, const Tracer& reference,
                             const Tracer& other);

// True when a hit lies within kGrazingBary of an edge of its triangle.
bool NearEdge(const Hit& hit);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_COMPARE_H_
