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

// Below this many events a comparison sort is faster than clearing and
// summing the radix sort's 8,192 counters.
constexpr size_t kRadixMinEvents = 1024;

// Sorts `events` (keys below 2^34: Event's) in ascending order: an LSD radix
// sort of three digits (12, 11 and 11 bits), each pass stable, with the three
// histograms counted in one read. Equal keys are identical events, so the
// result is std::sort's exactly.
void SortEvents(SweepScratch* scratch) {
  std::vector<uint64_t>* events = &scratch->events;
  std::vector<uint64_t>* spare = &scratch->sorted;
  const size_t n = events->size();
  if (n < kRadixMinEvents) {
    std::sort(events->begin(), events->end());
    return;
  }
  constexpr int kShift[3] = {0, 12, 23};
  constexpr uint64_t kMask[3] = {(1u << 12) - 1, (1u << 11) - 1, (1u << 11) - 1};
  std::vector<uint32_t>& counts = scratch->counts;
  counts.assign((1u << 12) + 2 * (1u << 11), 0);
  uint32_t* count[3] = {counts.data(), counts.data() + (1u << 12),
                        counts.data() + (1u << 12) + (1u << 11)};
  const uint64_t* in = events->data();
  for (size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) ++count[d][(in[i] >> kShift[d]) & kMask[d]];
  }
  spare->resize(n);
  uint64_t* a = events->data();
  uint64_t* b = spare->data();
  for (int d = 0; d < 3; ++d) {
    uint32_t sum = 0;
    for (uint64_t k = 0; k <= kMask[d]; ++k) {
      const uint32_t c = count[d][k];
      count[d][k] = sum;
      sum += c;
    }
    for (size_t i = 0; i < n; ++i) b[count[d][(a[i] >> kShift[d]) & kMask[d]]++] = a[i];
    std::swap(a, b);
  }
  events->swap(*spare);  // three passes: the sorted keys are in the spare buffer
}

void SweepAxis(const BuildRef* refs, size_t n, const AABB& box, int axis, const Config& config,
               SweepScratch* scratch, Split* best) {
  std::vector<uint64_t>* events = &scratch->events;
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
  SortEvents(scratch);
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
    SweepAxis(refs, n, node_box, axis, config, scratch, &best);
  }
  return best;
}

}  // namespace kdtree
