// The watertight test's common rejection for the 4 triangles of a leaf
// packet (cc/kdtree/leaf_layout.h) at once, for the single-ray traversal
// (traversal.cc). The packet kernel's RejectRays (ray_packet_kernel.cc) does
// the same for one triangle against a vector of rays.
#ifndef KDTREE_CC_KDTREE_PACKET_REJECT_H_
#define KDTREE_CC_KDTREE_PACKET_REJECT_H_

#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"

#include <immintrin.h>

namespace kdtree {

// Bit l set when packet lane l is certainly rejected by the watertight test:
// its three edge functions have certainly different exact signs (the largest
// beyond +EdgeErrorBound, the smallest beyond -EdgeErrorBound, watertight.h),
// or, with `behind` (tmin >= 0), its three vertex depths z = sz (v[kz] -
// o[kz]) are negative. SSE single precision performs the very IEEE operations
// of IntersectTriangleWatertight's first step (watertight.h) in the
// same order (no contraction: -ffp-contract=off), so a set bit is a lane that
// test rejects, and a clear bit means it decides exactly as without this step.
// (A NaN edge function may clear a bit the scalar test would set: that lane
// then gets the scalar test, which rejects it.)
inline int RejectMask4(const WatertightRay& r, const float* packet, bool behind) {
  const __m128 ox = _mm_set1_ps(r.ox), oy = _mm_set1_ps(r.oy), oz = _mm_set1_ps(r.oz);
  const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  __m128 x[3], y[3], z[3];
  for (int v = 0; v < 3; ++v) {
    const float* p = packet + 3 * v * kPacketLanes;
    z[v] = _mm_sub_ps(_mm_loadu_ps(p + r.kz * kPacketLanes), oz);
    x[v] = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(p + r.kx * kPacketLanes), ox), _mm_mul_ps(sx, z[v]));
    y[v] = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(p + r.ky * kPacketLanes), oy), _mm_mul_ps(sy, z[v]));
  }
  const __m128 e0 = _mm_sub_ps(_mm_mul_ps(x[2], y[1]), _mm_mul_ps(y[2], x[1]));
  const __m128 e1 = _mm_sub_ps(_mm_mul_ps(x[0], y[2]), _mm_mul_ps(y[0], x[2]));
  const __m128 e2 = _mm_sub_ps(_mm_mul_ps(x[1], y[0]), _mm_mul_ps(y[1], x[0]));
  // EdgeErrorBound (watertight.h): the same operations in the same order.
  const auto max_abs3 = [abs_mask](const __m128 v[3]) {
    return _mm_max_ps(_mm_max_ps(_mm_and_ps(v[0], abs_mask), _mm_and_ps(v[1], abs_mask)),
                      _mm_and_ps(v[2], abs_mask));
  };
  const __m128 l = _mm_max_ps(max_abs3(x), max_abs3(y));
  const __m128 depth = _mm_mul_ps(
      _mm_add_ps(max_abs3(z), _mm_set1_ps(watertight_internal::kEdgeBoundMinDepth)),
      _mm_set1_ps(watertight_internal::ShearWeight(r)));
  const __m128 bound =
      _mm_add_ps(_mm_mul_ps(_mm_set1_ps(watertight_internal::kEdgeBoundRel),
                            _mm_mul_ps(l, _mm_add_ps(l, depth))),
                 _mm_set1_ps(watertight_internal::kEdgeBoundAbs));
  // Certainly opposite signs: the largest beyond +bound, the smallest
  // beyond -bound (watertight.h SignsDisagree).
  const __m128 e_max = _mm_max_ps(_mm_max_ps(e0, e1), e2);
  const __m128 e_min = _mm_min_ps(_mm_min_ps(e0, e1), e2);
  __m128 reject = _mm_and_ps(_mm_cmpgt_ps(e_max, bound),
                             _mm_cmplt_ps(e_min, _mm_xor_ps(bound, _mm_set1_ps(-0.0f))));
  if (behind) {
    const __m128 zero = _mm_setzero_ps();
    const __m128 sz = _mm_set1_ps(r.sz);
    reject = _mm_or_ps(
        reject, _mm_and_ps(_mm_and_ps(_mm_cmplt_ps(_mm_mul_ps(sz, z[0]), zero),
                                      _mm_cmplt_ps(_mm_mul_ps(sz, z[1]), zero)),
                           _mm_cmplt_ps(_mm_mul_ps(sz, z[2]), zero)));
  }
  return _mm_movemask_ps(reject);
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PACKET_REJECT_H_
