// A packet of rays (ray.h: 8 floats each) turned into rows, one per float,
// in vector registers, per Highway target (Highway's per-target include
// guard): LoadRayRows, for the kd-tree's packet set-up
// (kdtree/ray_packet_setup.cc) and, through RayRows (ray_rows.h), for
// Embree's ray packets (embree_tracer.cc), so that both tracers load their
// rays the same way on every target.
#if defined(KDTREE_CC_GEOMETRY_RAY_ROWS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_GEOMETRY_RAY_ROWS_INL_H_
#undef KDTREE_CC_GEOMETRY_RAY_ROWS_INL_H_
#else
#define KDTREE_CC_GEOMETRY_RAY_ROWS_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Whether this target has TransposeRays: 16 float lanes, two rays a vector.
#if HWY_TARGET != HWY_SCALAR && HWY_MAX_BYTES == 64
#define KDTREE_HAS_TRANSPOSE_RAYS 1

// Rays [0, n <= 16) of `rays` (8 floats each) by component: c[k] lane r is
// ray r's float k (0 for r >= n). Eight loads (masked past ray n: AVX-512's
// masked loads do not fault) and three rounds of two-source permutes
// (ConcatEven / ConcatOdd, one VPERMT2PS each), where eight 16-lane gathers
// took 100 of a packet's 130 cycles of set-up in a microbenchmark
// (kdtree/leaf_bvh_packet_kernel.cc) and most of LoadLanes' time in a
// profile of morse-indoor's renders. In-process A/B (render_bench
// kd_bvh_packet, this path for full packets on AVX3_DL against the gathers
// on AVX3, 7 paired rounds, one process; 2026-12-07): camera pass 0.942 of
// the time on morse-indoor, 0.972-0.984 on city2, bunny, lost-empire and
// morse-trees, 1.000 on hairball-1m (renders 0.973-0.998); the control
// (gathers on both) 0.987-1.003 (renders 0.975-1.011). The masked loads
// for shorter packets (most shadow packets) came after; a second A/B with
// them, in a noisy state of the machine (morse-indoor's rounds 0.62-1.50),
// gave shadow passes of 0.953-1.008 on seven scenes, 0 mismatches.
template <class D>
HWY_INLINE void TransposeRays(D d, const float* rays, int n, hn::Vec<D> (&c)[8]) {
  static_assert(hn::MaxLanes(D()) == 16, "two rays a vector");
  using V = hn::Vec<D>;
  V a[8], b[8];
  for (int j = 0; j < 8; ++j) {
    const int avail = 8 * n - 16 * j;  // floats of rays [0, n) in this vector
    a[j] = avail >= 16 ? hn::LoadU(d, rays + 16 * j)
                       : hn::MaskedLoad(hn::FirstN(d, avail > 0 ? avail : 0), d, rays + 16 * j);
  }
  // b[j], j < 4: rays 4j..4j+3, floats 0, 2, 4, 6; b[4 + j]: floats 1, 3, 5, 7.
  for (int j = 0; j < 4; ++j) {
    b[j] = hn::ConcatEven(d, a[2 * j + 1], a[2 * j]);
    b[4 + j] = hn::ConcatOdd(d, a[2 * j + 1], a[2 * j]);
  }
  // a[2h + q + 4i], h < 2: rays 8h..8h+7, floats f and f + 4 for f = 2q + i.
  for (int i = 0; i < 2; ++i) {
    for (int h = 0; h < 2; ++h) {
      a[2 * h + 4 * i] = hn::ConcatEven(d, b[4 * i + 2 * h + 1], b[4 * i + 2 * h]);
      a[2 * h + 1 + 4 * i] = hn::ConcatOdd(d, b[4 * i + 2 * h + 1], b[4 * i + 2 * h]);
    }
  }
  for (int f = 0; f < 4; ++f) {
    const int q = f / 2, i = f % 2;
    c[f] = hn::ConcatEven(d, a[2 + q + 4 * i], a[q + 4 * i]);
    c[f + 4] = hn::ConcatOdd(d, a[2 + q + 4 * i], a[q + 4 * i]);
  }
}
#else
#undef KDTREE_HAS_TRANSPOSE_RAYS
#endif

// Rays [base, base + Lanes(d)) of rays [0, n <= 16) by component: c[k] lane j
// is ray base + j's float k, 0 for base + j >= n. TransposeRays where the
// target has it (16 lanes, base 0); elsewhere a gather per component, lanes
// from n on reading ray 0 (nothing at all when n is 0) and then zeroed.
template <class D>
HWY_INLINE void LoadRayRows(D d, const float* rays, int n, size_t base, hn::Vec<D> (&c)[8]) {
#ifdef KDTREE_HAS_TRANSPOSE_RAYS
  HWY_DASSERT(base == 0);
  TransposeRays(d, rays, n, c);
#else
  if (n <= 0) {
    for (int k = 0; k < 8; ++k) c[k] = hn::Zero(d);
    return;
  }
  const hn::RebindToSigned<D> di;
  const auto lane = hn::Iota(di, static_cast<int32_t>(base));
  const auto in = hn::Lt(lane, hn::Set(di, n));
  const auto index = hn::IfThenElseZero(in, hn::Mul(lane, hn::Set(di, 8)));
  for (int k = 0; k < 8; ++k) {
    c[k] = hn::IfThenElseZero(hn::RebindMask(d, in), hn::GatherIndex(d, rays + k, index));
  }
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_GEOMETRY_RAY_ROWS_INL_H_
