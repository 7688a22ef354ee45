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

}  // namespace kdtree
