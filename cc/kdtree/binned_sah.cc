#include "cc/kdtree/binned_sah.h"

#include <emmintrin.h>

#include <algorithm>

#include "cc/kdtree/sah_cost.h"

namespace kdtree {
namespace {

// The candidate planes of `bins` bins (bins - 1), rounded up to whole SSE
// vectors.
int PaddedPlanes(int bins) { return (bins - 1 + 3) / 4 * 4; }

// Sizes the per-plane arrays once for this bin count (a resize per node
// would refill them every time).
void SizePlaneArrays(int bins, BinScratch* s) {
  const size_t padded = static_cast<size_t>(PaddedPlanes(bins));
  if (s->n_left.size() == padded) return;
  s->n_left.assign(padded, 0.0f);
  s->n_right.assign(padded, 0.0f);
  s->cost.assign(padded, 0.0f);
  s->plane.assign(padded, 0.0f);
}

// `n` zeroed counters in `v` (resized only when the bin count changes).
void ZeroCounters(size_t n, std::vector<uint32_t>* v) {
  if (v->size() != n) v->resize(n);
  std::fill(v->begin(), v->end(), 0u);
}

// BinOf on four lanes: the same IEEE operations in the same order (sub, mul,
// div are exactly rounded per lane, so every lane equals the scalar value),
// then the same clamp: max(f, 0) is 0 for NaN (MAXPS returns its second
// operand), and min(., bins - 1) truncates to the same integer as the scalar
// "f >= bins -> bins - 1" because every f in [bins - 1, bins) truncates to
// bins - 1 anyway.
inline __m128i BinOf4(__m128 x, __m128 lo, __m128 bins, __m128 extent, __m128 last) {
  const __m128 f = _mm_div_ps(_mm_mul_ps(_mm_sub_ps(x, lo), bins), extent);
  return _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), last));
}

// Surface areas 2 (ex ey + ey ez + ez ex) of four boxes, in AABB::SurfaceArea's
// order of operations.
inline __m128 SurfaceArea4(__m128 ex, __m128 ey, __m128 ez) {
  const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(ex, ey), _mm_mul_ps(ey, ez)),
                                _mm_mul_ps(ez, ex));
  return _mm_mul_ps(_mm_set1_ps(2.0f), sum);
}

// The report's relaxed SAH (SplitCost without full_sah) of planes 1..bins-1
// into s->cost[0..bins-2], four planes at a time: BinPlane, the children's
// extents and SplitCost's products and sums in their scalar order, so each
// cost is bit-identical to SplitCost's.
void RelaxedCosts(const AABB& box, int axis, int bins, BinScratch* s) {
  const Vec3 e = box.Extent();
  const float lo = box.lo[axis], hi = box.hi[axis];
  const float extent = hi - lo;
  const int padded = PaddedPlanes(bins);
  // SweepCounts sized every array to `padded`; the lanes past bins - 1 hold
  // whatever an earlier node left there and their costs are never read.
  const __m128 vlo = _mm_set1_ps(lo), vhi = _mm_set1_ps(hi), vext = _mm_set1_ps(extent);
  const __m128 vbins = _mm_set1_ps(static_cast<float>(bins));
  const __m128 ex = _mm_set1_ps(e.x), ey = _mm_set1_ps(e.y), ez = _mm_set1_ps(e.z);
  for (int i = 0; i < padded; i += 4) {
    const __m128 index = _mm_setr_ps(static_cast<float>(i + 1), static_cast<float>(i + 2),
                                     static_cast<float>(i + 3), static_cast<float>(i + 4));
    const __m128 plane = _mm_add_ps(vlo, _mm_div_ps(_mm_mul_ps(vext, index), vbins));
    const __m128 left = _mm_sub_ps(plane, vlo);   // the left child's extent on `axis`
    const __m128 right = _mm_sub_ps(vhi, plane);  // the right child's
    __m128 sa_l, sa_r;
    if (axis == 0) {
      sa_l = SurfaceArea4(left, ey, ez);
      sa_r = SurfaceArea4(right, ey, ez);
    } else if (axis == 1) {
      sa_l = SurfaceArea4(ex, left, ez);
      sa_r = SurfaceArea4(ex, right, ez);
    } else {
      sa_l = SurfaceArea4(ex, ey, left);
      sa_r = SurfaceArea4(ex, ey, right);
    }
    const __m128 cost = _mm_add_ps(_mm_mul_ps(sa_l, _mm_loadu_ps(&s->n_left[i])),
                                   _mm_mul_ps(sa_r, _mm_loadu_ps(&s->n_right[i])));
    _mm_storeu_ps(&s->cost[i], cost);
    _mm_storeu_ps(&s->plane[i], plane);
  }
}

// Evaluates the planes of one axis from its counts; updates *best when a
// candidate is strictly cheaper (axes and planes in increasing order, so the
// first strict minimum wins).
void SweepCounts(const uint32_t* starts, const uint32_t* ends, size_t n, const AABB& box,
                 int axis, int bins, const Config& config, BinScratch* s, Split* best) {
  const float lo = box.lo[axis];
  const float extent = box.hi[axis] - lo;
  float n_left = 0.0f, n_right = static_cast<float>(n);
  if (!config.full_sah) {
    SizePlaneArrays(bins, s);
    for (int i = 0; i + 1 < bins; ++i) {
      n_left += static_cast<float>(starts[i]);
      n_right -= static_cast<float>(ends[i]);
      s->n_left[i] = n_left;
      s->n_right[i] = n_right;
    }
    RelaxedCosts(box, axis, bins, s);
    for (int i = 0; i + 1 < bins; ++i) {
      const float cost = s->cost[i];
      if (!best->found || cost < best->cost) {
        best->found = true;
        best->axis = axis;
        best->pos = s->plane[i];
        best->cost = cost;
      }
    }
    return;
  }
  for (int i = 0; i + 1 < bins; ++i) {
    n_left += static_cast<float>(starts[i]);
    n_right -= static_cast<float>(ends[i]);
    const float plane = BinPlane(lo, extent, i + 1, bins);
    const float cost = SplitCost(box, axis, plane, n_left, n_right, config);
    if (!best->found || cost < best->cost) {
      best->found = true;
      best->axis = axis;
      best->pos = plane;
      best->cost = cost;
    }
  }
}

// One axis (the driving axis): counts, then sweeps. The bins of four
// references at a time come from BinOf4 (the scalar BinOf's value in every
// lane); the rest from BinOf.
template <class Ref>
void SweepAxis(const Ref* refs, const AABB* boxes, size_t n, const AABB& box, int axis, int bins,
               const Config& config, BinScratch* s, Split* best) {
  const float lo = box.lo[axis];
  const float extent = box.hi[axis] - lo;
  if (!(extent > 0.0f)) return;
  // One histogram per lane (kLanes copies of `bins` counters), summed at the
  // end: neighbouring references mostly fall into the same bin, and four
  // increments of one counter in a row wait on each other's stores.
  constexpr int kLanes = 4;
  ZeroCounters(kLanes * static_cast<size_t>(bins), &s->starts);
  ZeroCounters(kLanes * static_cast<size_t>(bins), &s->ends);
  uint32_t* st = s->starts.data();
  uint32_t* en = s->ends.data();
  const __m128 vlo = _mm_set1_ps(lo), vext = _mm_set1_ps(extent);
  const __m128 fbins = _mm_set1_ps(static_cast<float>(bins));
  const __m128 last = _mm_set1_ps(static_cast<float>(bins - 1));
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    __m128 box_lo, box_hi;
    LoadAxis4(refs + i, boxes, axis, &box_lo, &box_hi);
    alignas(16) int l[4], h[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(l), BinOf4(box_lo, vlo, fbins, vext, last));
    _mm_store_si128(reinterpret_cast<__m128i*>(h), BinOf4(box_hi, vlo, fbins, vext, last));
    ++st[l[0]];
    ++st[bins + l[1]];
    ++st[2 * bins + l[2]];
    ++st[3 * bins + l[3]];
    ++en[h[0]];
    ++en[bins + h[1]];
    ++en[2 * bins + h[2]];
    ++en[3 * bins + h[3]];
  }
  for (; i < n; ++i) {
    const AABB& b = BoxOf(refs[i], boxes);
    ++st[BinOf(b.lo[axis], lo, extent, bins)];
    ++en[BinOf(b.hi[axis], lo, extent, bins)];
  }
  for (int k = 1; k < kLanes; ++k) {
    for (int b = 0; b < bins; ++b) {
      st[b] += st[k * bins + b];
      en[b] += en[k * bins + b];
    }
  }
  SweepCounts(s->starts.data(), s->ends.data(), n, box, axis, bins, config, s, best);
}

template <class Ref>
void CountBins(const Ref* refs, const AABB* boxes, size_t n, const AABB& box, int bins,
               BinScratch* s) {
  // Two sets of the three histograms (even and odd references), summed at
  // the end, so that consecutive references do not wait on each other's
  // increments (see SweepAxis).
  const size_t set = 3 * static_cast<size_t>(bins);
  ZeroCounters(2 * set, &s->starts);
  ZeroCounters(2 * set, &s->ends);
  const __m128 lo = _mm_setr_ps(box.lo.x, box.lo.y, box.lo.z, 0.0f);
  // A flat axis divides by 0 here; its lanes are clamped like any other and
  // its counts are never read (FindBinnedSahSplit skips the axis).
  const __m128 extent = _mm_setr_ps(box.hi.x - box.lo.x, box.hi.y - box.lo.y,
                                    box.hi.z - box.lo.z, 1.0f);
  const __m128 fbins = _mm_set1_ps(static_cast<float>(bins));
  const __m128 last = _mm_set1_ps(static_cast<float>(bins - 1));
  uint32_t* st = s->starts.data();
  uint32_t* en = s->ends.data();
  for (size_t i = 0; i < n; ++i) {
    // lo.x lo.y lo.z hi.x and hi.x hi.y hi.z plus the word after the box
    // (BuildRef::tri, or the next box's lo.x): the fourth lanes are unused.
    const float* b = Coords(BoxOf(refs[i], boxes));
    alignas(16) int l[4], h[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(l),
                    BinOf4(_mm_loadu_ps(b), lo, fbins, extent, last));
    _mm_store_si128(reinterpret_cast<__m128i*>(h),
                    BinOf4(_mm_loadu_ps(b + 3), lo, fbins, extent, last));
    uint32_t* const sti = st + (i & 1) * set;
    uint32_t* const eni = en + (i & 1) * set;
    ++sti[l[0]];
    ++sti[bins + l[1]];
    ++sti[2 * bins + l[2]];
    ++eni[h[0]];
    ++eni[bins + h[1]];
    ++eni[2 * bins + h[2]];
  }
  for (size_t b = 0; b < set; ++b) {
    st[b] += st[set + b];
    en[b] += en[set + b];
  }
}

template <class Ref>
Split FindSplit(const Ref* refs, const AABB* boxes, size_t n, const AABB& node_box,
                const Config& config, BinScratch* scratch) {
  Split best;
  if (config.use_driving_axis) {
    SweepAxis(refs, boxes, n, node_box, node_box.LongestAxis(), config.bins, config, scratch,
              &best);
    return best;
  }
  // All three axes from one pass over the references.
  CountBins(refs, boxes, n, node_box, config.bins, scratch);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(node_box.hi[axis] - node_box.lo[axis] > 0.0f)) continue;
    const size_t off = static_cast<size_t>(axis) * config.bins;
    SweepCounts(scratch->starts.data() + off, scratch->ends.data() + off, n, node_box, axis,
                config.bins, config, scratch, &best);
  }
  return best;
}

}  // namespace

void CountBinsAllAxes(const BuildRef* refs, size_t n, const AABB& box, int bins,
                      BinScratch* scratch) {
  CountBins(refs, nullptr, n, box, bins, scratch);
}

Split FindBinnedSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* scratch) {
  return FindSplit(refs, nullptr, n, node_box, config, scratch);
}

Split FindBinnedSahSplit(const IndexRef* refs, const AABB* boxes, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* scratch) {
  return FindSplit(refs, boxes, n, node_box, config, scratch);
}

}  // namespace kdtree
