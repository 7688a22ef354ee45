// One traced ray and its result: the unit of the ray dump (ray_dump.h), of the
// counting pass (traversal_counts.h) and of tracer comparisons (compare.h).
#ifndef KDTREE_CC_RENDER_RAY_RECORD_H_
#define KDTREE_CC_RENDER_RAY_RECORD_H_

#include <cstdint>

#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

enum class RayKind : uint8_t {
  kPrimary = 0,  // closest hit: tri, t, u, v are the result
  kShadow = 1,   // any hit towards a point light: only `hit` is the result
  kAo = 2,       // any hit within the ambient-occlusion distance
};
inline constexpr int kNumRayKinds = 3;
const char* RayKindName(RayKind kind);  // "primary", "shadow", "ao"

// 56 bytes, no padding; the dump file stores exactly this layout.
struct RayRecord {
  Vec3 origin;
  Vec3 dir;
  float tmin = 0;
  float tmax = 0;
  RayKind kind = RayKind::kPrimary;
  uint8_t hit = 0;        // 1 when hit (closest hit found, or occluded)
  uint16_t light = 0;     // shadow: light index; ao: sample index; primary: 0
  uint32_t pixel = 0;     // y * width + x of the primary ray it came from
  uint32_t tri = kNoHit;  // primary: triangle hit (kNoHit on a miss); else kNoHit
  float t = 0;            // primary: distance of the hit (0 on a miss)
  float u = 0, v = 0;     // primary: barycentrics of the hit

  Ray ray() const {
    Ray r;
    r.origin = origin;
    r.dir = dir;
    r.tmin = tmin;
    r.tmax = tmax;
    return r;
  }
  bool operator==(const RayRecord& o) const;
};
static_assert(sizeof(RayRecord) == 56, "RayRecord is the 56-byte dump record");

// The record of `ray` with its result unset (hit = 0, tri = kNoHit).
RayRecord RecordOf(const Ray& ray, RayKind kind, uint32_t pixel = 0, uint16_t light = 0);
// The record of a primary ray and its closest hit.
RayRecord PrimaryRecord(const Ray& ray, const Hit& hit, uint32_t pixel = 0);
// The record of a shadow or AO ray and whether it is occluded.
RayRecord SecondaryRecord(const Ray& ray, RayKind kind, bool occluded, uint32_t pixel = 0,
                          uint16_t light = 0);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_RAY_RECORD_H_
