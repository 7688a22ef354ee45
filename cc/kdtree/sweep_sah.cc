#include "cc/kdtree/sweep_sah.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "cc/kdtree/sah_cost.h"

namespace kdtree {
namespace {

// Event types in sweep order at one position.
constexpr uint64_t kEnd = 0, kPlanar = 1, kStart = 2;

// Float -> unsigned key with the same order (-0 is folded into +0 first).
uint32_t OrderedBits(float x) {
  x += 0.0f;  // -0 -> +0
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float FromOrderedBits(uint32_t u) {
  u = (u & 0x80000000u) ? (u & 0x7fffffffu) : ~u;
  float x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

uint64_t Event(float pos, uint64_t type) { return (uint64_t{OrderedBits(pos)} << 2) | type; }

void SweepAxis(const BuildRef* refs, size_t n, const AABB& box, int axis, const Config& config,
               std::vector<uint64_t>* events, Split* best) {
  const float box_lo = box.lo[axis], box_hi = box.hi[axis];
  if (!(box_hi > box_lo)) return;
  events->clear();
  for (size_t i = 0; i < n; ++i) {
    const float lo = refs[i].box.lo[axis], hi = refs[i].box.hi[axis];
    if (lo == hi) {
      events->push_back(Event(lo, kPlanar));
    } else {
      events->push_back(Event(lo, kStart));
      events->push_back(Event(hi, kEnd));
    }
  }
  std::sort(events->begin(), events->end());
  const uint64_t* e = events->data();
  const size_t count = events->size();
  auto consider = [&](float plane, size_t nl, size_t nr) {
    if (!(plane > box_lo && plane < box_hi)) return;
    const float cost =
        SplitCost(box, axis, plane, static_cast<float>(nl), static_cast<float>(nr), config);
    if (!best->found || cost < best->cost) {
      best->found = true;
      best->axis = axis;
      best->pos = plane;
      best->cost = cost;
    }
  };
  size_t n_left = 0, n_right = n;
  float prev = -INFINITY;
  for (size_t i = 0; i < count;) {
    const uint64_t key = e[i] >> 2;
    size_t ends = 0, planars = 0, starts = 0;
    for (; i < count && (e[i] >> 2) == key; ++i) {
      const uint64_t type = e[i] & 3u;
      ends += type == kEnd;
      planars += type == kPlanar;
      starts += type == kStart;
    }
    const float plane = FromOrderedBits(static_cast<uint32_t>(key));
    const float next = i < count ? FromOrderedBits(static_cast<uint32_t>(e[i] >> 2)) : INFINITY;
    // The float just below: no event in (prev, below], so the counts are
    // those before this position.
    const float below = std::nextafter(plane, -INFINITY);
    if (below > prev) consider(below, n_left, n_right);
    n_right -= ends + planars;
    consider(plane, n_left + planars, n_right + planars);
    n_left += starts + planars;
    // The float just above: no event in [above, next), so the counts are
    // those after this position (in-plane triangles on the left only).
    const float above = std::nextafter(plane, INFINITY);
    if (above < next) consider(above, n_left, n_right);
    prev = plane;
  }
}

}  // namespace

Split FindSweepSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                        const Config& config, SweepScratch* scratch) {
  Split best;
  for (int axis = 0; axis < 3; ++axis) {
    SweepAxis(refs, n, node_box, axis, config, &scratch->events, &best);
  }
  return best;
}

}  // namespace kdtree
