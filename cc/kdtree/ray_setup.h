// Per-ray set-up of the kd-tree traversal (traversal.h): the reciprocal
// direction, the spatial tolerance delta and its per-axis form in t, the
// padded interval of the ray in the root box, the slack of the termination
// test, and the watertight ray (watertight.h). traversal.h explains each.
//
// SetUpRay runs in SSE when no direction component is zero (the common case):
// two divisions of 4 lanes instead of seven scalar ones, and the three slabs
// at once. Every lane performs the very IEEE operations of the scalar code in
// the same order (no contraction: -ffp-contract=off; MINPS/MAXPS select the
// operand the scalar comparisons select, signed zeros included), so it writes
// exactly what SetUpRayScalar writes (ray_setup_test.cc checks every field,
// bit for bit). Rays with a zero component (parallel to an axis) take the
// scalar code, which handles them.
#ifndef KDTREE_CC_KDTREE_RAY_SETUP_H_
#define KDTREE_CC_KDTREE_RAY_SETUP_H_

#include <cmath>
#include <utility>

#include "cc/geometry/aabb.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"

#include <immintrin.h>

namespace kdtree {

namespace ray_setup {
constexpr float kPad = 4e-7f;  // about 3.4 float ulps, >= 2 gamma(3) (Ize 2013)
constexpr float kHitSlack = 64.0f * 5.9604645e-8f;    // 64 * 2^-24, see traversal.h
// What the tolerance costs (render_bench, sah-packet, 2026-12-06): with a
// thousandth of it (not exact; a bound on what any tighter analysis could
// buy) the shadow pass of the single-ray traversal took 13-19 % less on
// rungholt-1m, lost-empire and stk-candela-city, and nothing on city; with
// half of it, nothing measurable on those scenes, bunny, city or
// morse-buildings. A bound from the largest triangle L instead of the
// scene, for nodes within 2 L of a shadow ray's origin (delta = 16 * 2^-24
// * 3 L, by the same argument), bought at most 2.5 % (rungholt-1m) and cost
// 3-4 % on bunny, city and stk-candela-city: not kept. What is kept is a
// tolerance relative to the node's interval for shadow rays with the
// watertight test (IntervalTol below; traversal.h).
constexpr float kSpatialTol = 16.0f * 5.9604645e-8f;  // 16 * 2^-24, see traversal.h

// Inputs are finite here, so a plain comparison equals std::fmax without the
// libm call.
inline float Max(float a, float b) { return a > b ? a : b; }

// The planes' tolerance in t for shadow rays searched with the watertight
// test (traversal.h, "Robustness"): 16 * 2^-24 * max(|t_entry|, |t_exit|)
// plus the smallest normal float, from the interval of a node or one of its
// ancestors. The single-ray traversal computes it when it pushes a node,
// the packet kernel per lane when it pops one, with these operations.
constexpr float kRelTol = 16.0f * 5.9604645e-8f;  // 16 * 2^-24
constexpr float kRelTolFloor = 0x1p-126f;
inline float IntervalTol(float t_entry, float t_exit) {
  return kRelTol * Max(std::fabs(t_entry), std::fabs(t_exit)) + kRelTolFloor;
}

}  // namespace ray_setup

struct RaySetup {
  float org[3];
  float inv[3];    // 1 / dir
  float tol[3];    // delta / |dir[k]|: a plane's thickness in t
  float delta;     // spatial tolerance
  float t_entry, t_exit;  // the padded interval in the root box
  float slack;     // of the termination test
  bool negative[3];       // sign bits of dir
  WatertightRay wray;
};

// For a ray that passed SanitizeRay (ray_check.h). False when it misses the
// padded box (the other fields are then unspecified).
inline bool SetUpRayScalar(const Ray& ray, const AABB& box, RaySetup* s) {
  using ray_setup::Max;
  for (int k = 0; k < 3; ++k) {
    s->org[k] = ray.origin[k];
    s->inv[k] = 1.0f / ray.dir[k];
    s->negative[k] = std::signbit(ray.dir[k]);
  }
  // The largest coordinate difference between the ray origin and the box.
  float reach = 0;
  for (int k = 0; k < 3; ++k) {
    reach = Max(reach, Max(std::fabs(box.lo[k] - ray.origin[k]),
                           std::fabs(box.hi[k] - ray.origin[k])));
  }
  const float delta = ray_setup::kSpatialTol * reach;
  s->delta = delta;
  for (int k = 0; k < 3; ++k) s->tol[k] = delta * std::fabs(s->inv[k]);
  // The slabs, each widened by delta in space on top of the relative padding.
  float lo = ray.tmin, hi = ray.tmax;
  for (int k = 0; k < 3; ++k) {
    const float o = ray.origin[k];
    if (ray.dir[k] == 0.0f) {
      if (!(box.lo[k] - o <= delta && o - box.hi[k] <= delta)) return false;
      continue;
    }
    float tn = (box.lo[k] - o) * s->inv[k], tf = (box.hi[k] - o) * s->inv[k];
    if (tn > tf) std::swap(tn, tf);
    tn -= std::fabs(tn) * ray_setup::kPad + s->tol[k];
    tf += std::fabs(tf) * ray_setup::kPad + s->tol[k];
    if (tn > lo) lo = tn;
    if (tf < hi) hi = tf;
    if (!(lo <= hi)) return false;
  }
  s->t_entry = lo;
  s->t_exit = hi;
  s->wray = MakeWatertightRay(ray);
  // The ray's largest distance, in t, to the box along its dominant axis
  // (the watertight frame's kz): no triangle vertex is deeper, so it scales
  // every triangle's t error.
  const int k = s->wray.kz;
  const float o = ray.origin[k];
  const float depth = Max(std::fabs(box.lo[k] - o), std::fabs(box.hi[k] - o));
  s->slack = ray_setup::kHitSlack * (depth / std::fabs(ray.dir[k]));
  return true;
}

// Always inlined: GCC otherwise calls it from the closest-hit traversal, and
// its results go through memory (in one render_bench run, kd_origin, 7 paired
// rounds: inlined, T_R 1.028-1.039 on five of six scenes, dragon 1.003).
inline __attribute__((always_inline)) bool SetUpRay(const Ray& ray, const AABB& box,
                                                    RaySetup* s) {
  using ray_setup::Max;
  const __m128 d = _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 1.0f);
  if ((_mm_movemask_ps(_mm_cmpeq_ps(d, _mm_setzero_ps())) & 7) != 0) {
    return SetUpRayScalar(ray, box, s);
  }
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 o = _mm_setr_ps(ray.origin.x, ray.origin.y, ray.origin.z, 0.0f);
  const __m128 dl = _mm_sub_ps(_mm_setr_ps(box.lo.x, box.lo.y, box.lo.z, 0.0f), o);
  const __m128 dh = _mm_sub_ps(_mm_setr_ps(box.hi.x, box.hi.y, box.hi.z, 0.0f), o);
  const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), d);
  alignas(16) float adl[4], adh[4], v[4];
  _mm_store_ps(adl, _mm_and_ps(dl, abs_mask));
  _mm_store_ps(adh, _mm_and_ps(dh, abs_mask));
  float reach = 0;
  for (int k = 0; k < 3; ++k) reach = Max(reach, Max(adl[k], adh[k]));
  const float delta = ray_setup::kSpatialTol * reach;
  s->delta = delta;
  const __m128 tol = _mm_mul_ps(_mm_set1_ps(delta), _mm_and_ps(inv, abs_mask));
  const __m128 tn = _mm_mul_ps(dl, inv), tf = _mm_mul_ps(dh, inv);
  // Scalar: if (tn > tf) swap. MINPS(a, b) = a < b ? a : b; MAXPS(a, b) =
  // a > b ? a : b.
  __m128 t0 = _mm_min_ps(tf, tn), t1 = _mm_max_ps(tn, tf);
  const __m128 pad = _mm_set1_ps(ray_setup::kPad);
  t0 = _mm_sub_ps(t0, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t0, abs_mask), pad), tol));
  t1 = _mm_add_ps(t1, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t1, abs_mask), pad), tol));
  alignas(16) float a0[4], a1[4];
  _mm_store_ps(a0, t0);
  _mm_store_ps(a1, t1);
  float lo = ray.tmin, hi = ray.tmax;
  for (int k = 0; k < 3; ++k) {
    if (a0[k] > lo) lo = a0[k];
    if (a1[k] < hi) hi = a1[k];
  }
  // lo only grows and hi only shrinks: the scalar per-axis exit is this.
  if (!(lo <= hi)) return false;
  s->t_entry = lo;
  s->t_exit = hi;
  _mm_storeu_ps(v, inv);
  for (int k = 0; k < 3; ++k) s->inv[k] = v[k];
  _mm_storeu_ps(v, tol);
  for (int k = 0; k < 3; ++k) s->tol[k] = v[k];
  s->org[0] = ray.origin.x;
  s->org[1] = ray.origin.y;
  s->org[2] = ray.origin.z;
  s->negative[0] = std::signbit(ray.dir.x);
  s->negative[1] = std::signbit(ray.dir.y);
  s->negative[2] = std::signbit(ray.dir.z);
  // MakeWatertightRay's three divisions and the slack's one, in one.
  WatertightRay& w = s->wray;
  WatertightAxes(ray.dir, &w.kx, &w.ky, &w.kz);
  const int kz = w.kz;
  const float dz = ray.dir[kz];
  const float depth = Max(adl[kz], adh[kz]);
  _mm_store_ps(v, _mm_div_ps(_mm_setr_ps(ray.dir[w.kx], ray.dir[w.ky], 1.0f, depth),
                             _mm_setr_ps(dz, dz, dz, std::fabs(dz))));
  w.sx = v[0];
  w.sy = v[1];
  w.sz = v[2];
  s->slack = ray_setup::kHitSlack * v[3];
  w.ox = ray.origin[w.kx];
  w.oy = ray.origin[w.ky];
  w.oz = ray.origin[kz];
  w.origin = ray.origin;
  w.dir = ray.dir;
  return true;
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RAY_SETUP_H_
