#include "cc/kdtree/median_split.h"

namespace kdtree {

Split FindMedianSplit(const AABB& node_box) {
  Split s;
  s.axis = node_box.LongestAxis();
  const float lo = node_box.lo[s.axis], hi = node_box.hi[s.axis];
  if (!(hi > lo)) return s;
  s.pos = (lo + hi) * 0.5f;
  s.found = true;
  return s;
}

}  // namespace kdtree
