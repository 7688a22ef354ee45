#include "cc/render/ray_record.h"

#include <cstring>

namespace kdtree {

const char* RayKindName(RayKind kind) {
  switch (kind) {
    case RayKind::kPrimary: return "primary";
    case RayKind::kShadow: return "shadow";
    case RayKind::kAo: return "ao";
  }
  return "unknown";
}

// Bitwise: the record has no padding (static_assert in the header), and
// bitwise equality is what "the same ray" means for a reproducible dump.
bool RayRecord::operator==(const RayRecord& o) const { return std::memcmp(this, &o, sizeof(*this)) == 0; }

RayRecord RecordOf(const Ray& ray, RayKind kind, uint32_t pixel, uint16_t light) {
  RayRecord rec;
  rec.origin = ray.origin;
  rec.dir = ray.dir;
  rec.tmin = ray.tmin;
  rec.tmax = ray.tmax;
  rec.kind = kind;
  rec.light = light;
  rec.pixel = pixel;
  return rec;
}

RayRecord PrimaryRecord(const Ray& ray, const Hit& hit, uint32_t pixel) {
  RayRecord rec = RecordOf(ray, RayKind::kPrimary, pixel);
  rec.hit = hit.hit();
  if (hit.hit()) {
    rec.tri = hit.tri;
    rec.t = hit.t;
    rec.u = hit.u;
    rec.v = hit.v;
  }
  return rec;
}

RayRecord SecondaryRecord(const Ray& ray, RayKind kind, bool occluded, uint32_t pixel,
                          uint16_t light) {
  RayRecord rec = RecordOf(ray, kind, pixel, light);
  rec.hit = occluded;
  return rec;
}

}  // namespace kdtree
