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
//
// The traversal enters through SanitizeAndSetUpRay: one vector test finds
// the common ray, which SanitizeRay would leave as it is, and the box, the
// reach and the interval stay in vectors to the end (lane k is axis k).
// Against SanitizeRay then the previous SetUpRay (scalar checks, the box
// read a float at a time, the lanes stored and reread as scalars), in one
// render_bench process (sah-packet, 9 paired rounds, the old code on a
// second, identical tree): the camera pass 3-8 % shorter on bunny, city2,
// lost-empire, courtyard-1m and stk-candela-city (T_R 2-6 %), the shadow
// pass 0-2.5 %; the same code on both trees 0.999-1.010.
//
// What the set-up costs now (render_bench, sah-packet, one process, 7 paired
// rounds, the variant's code on a second, identical tree, each pass less its
// replay; bunny, city2, lost-empire, teapots; 2026-12-06): a second,
// independent SanitizeAndSetUpRay per ray made the camera pass 1.29-1.36
// times as long and the shadow pass 1.06-1.15, about 14 ns a camera ray; six
// dependent multiplications by one on the reciprocal (18 cycles more on its
// chain, six instructions) 1.04-1.06 and 0.99-1.02 (the same code on both
// trees: 1.00-1.01). Yet a camera ray that misses the root box, which pays
// the set-up up to the box test and nothing else, costs us 7.5-7.9 ns and
// Embree 9.6-10.3 on all 25 standard scenes (render_bench --classes), so the
// set-up is not where single rays lose. Tried and not kept (the same A/B, six scenes):
// the watertight frame's components by one byte shuffle of the vectors (a
// table of PSHUFB controls indexed by the axes WatertightAxes' branches
// choose) instead of the selects, the sign bytes in one store: camera pass
// 1.01-1.03 (control 0.99-1.00); the sanitising, the set-up and the
// root-box test inlined into the caller and the traversal out of line, so
// that a ray that misses the box never enters its stack frame: 0.99-1.02
// (control 0.99-1.01).
#ifndef KDTREE_CC_KDTREE_RAY_SETUP_H_
#define KDTREE_CC_KDTREE_RAY_SETUP_H_

#include <cmath>
#include <limits>
#include <utility>

#include "cc/geometry/aabb.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/ray_check.h"
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
  // By axis (lane 3: padding, so that a vector store fills each).
  alignas(16) float org[4];
  alignas(16) float inv[4];    // 1 / dir
  alignas(16) float tol[4];    // delta / |dir[k]|: a plane's thickness in t
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

namespace ray_setup {

// The common ray: finite components, every direction component a normal
// float, tmin <= tmax; SanitizeRay leaves it as it is. o = (ox, oy, oz, 0),
// d = (dx, dy, dz, 1).
inline __attribute__((always_inline)) bool IsCommonRay(__m128 o, __m128 d, const Ray& ray) {
  // x - x is 0 for a finite x, NaN otherwise.
  const __m128 finite = _mm_cmpord_ps(_mm_sub_ps(o, o), _mm_sub_ps(d, d));
  const __m128 normal =
      _mm_cmpge_ps(_mm_and_ps(d, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff))),
                   _mm_set1_ps(std::numeric_limits<float>::min()));
  return _mm_movemask_ps(_mm_and_ps(finite, normal)) == 15 && ray.tmin <= ray.tmax;
}

// What a box test reads of the set-up: s->org, s->inv and s->negative from
// o = (ox, oy, oz, 0), inv = 1 / d and d = (dx, dy, dz, 1) (SetUpVector and
// SetUpCommonBoxRay).
inline __attribute__((always_inline)) void StoreBoxRay(__m128 o, __m128 inv, __m128 d,
                                                       RaySetup* s) {
  _mm_store_ps(s->org, o);
  _mm_store_ps(s->inv, inv);
  const int sign = _mm_movemask_ps(d);
  s->negative[0] = sign & 1;
  s->negative[1] = (sign >> 1) & 1;
  s->negative[2] = (sign >> 2) & 1;
}

// SetUpRay's vector path for a ray with every direction component nonzero:
// o = (ox, oy, oz, 0), d = (dx, dy, dz, 1). Lane k of every vector is axis
// k; the reach, the three slabs and the root interval are computed in
// lanes, with the scalar code's operations and MINPS / MAXPS / MINSS /
// MAXSS operand orders (which select what the scalar comparisons select,
// NaN and signed zeros included); the watertight frame's three divisions
// and the slack's share one vector division.
inline __attribute__((always_inline)) bool SetUpVector(__m128 o, __m128 d, const Ray& ray,
                                                       const AABB& box, RaySetup* s) {
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 xyz = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
  // The box's six floats, read in place (a copy to the stack first made the
  // second read wait for two stores).
  static_assert(sizeof(AABB) == 6 * sizeof(float), "box: lo then hi, packed");
  const float* b = &box.lo.x;
  const __m128 lo_v = _mm_loadu_ps(b);  // lane 3: hi.x, masked below
  const __m128 hi_raw = _mm_loadu_ps(b + 2);
  const __m128 hi_v = _mm_shuffle_ps(hi_raw, hi_raw, _MM_SHUFFLE(0, 3, 2, 1));
  const __m128 dl = _mm_sub_ps(lo_v, o), dh = _mm_sub_ps(hi_v, o);
  const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), d);
  // depth[k] = Max(|dl|, |dh|); reach = their largest (all >= 0, no NaN:
  // any order gives the scalar loop's bits).
  const __m128 depth = _mm_max_ps(_mm_and_ps(dl, abs_mask), _mm_and_ps(dh, abs_mask));
  __m128 reach = _mm_and_ps(depth, xyz);
  reach = _mm_max_ps(reach, _mm_shuffle_ps(reach, reach, _MM_SHUFFLE(1, 0, 3, 2)));
  reach = _mm_max_ps(reach, _mm_shuffle_ps(reach, reach, _MM_SHUFFLE(2, 3, 0, 1)));
  const __m128 delta = _mm_mul_ps(_mm_set1_ps(kSpatialTol), reach);
  const __m128 tol = _mm_mul_ps(delta, _mm_and_ps(inv, abs_mask));
  const __m128 tn = _mm_mul_ps(dl, inv), tf = _mm_mul_ps(dh, inv);
  // Scalar: if (tn > tf) swap. MINPS(a, b) = a < b ? a : b; MAXPS(a, b) =
  // a > b ? a : b.
  __m128 t0 = _mm_min_ps(tf, tn), t1 = _mm_max_ps(tn, tf);
  const __m128 pad = _mm_set1_ps(kPad);
  t0 = _mm_sub_ps(t0, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t0, abs_mask), pad), tol));
  t1 = _mm_add_ps(t1, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t1, abs_mask), pad), tol));
  // Scalar, per axis: if (t0 > lo) lo = t0 (MAXSS(t0, lo)); if (t1 < hi)
  // hi = t1 (MINSS(t1, hi)). lo only grows and hi only shrinks: the scalar
  // per-axis exit is the test after the three.
  __m128 lo = _mm_max_ss(t0, _mm_set_ss(ray.tmin));
  __m128 hi = _mm_min_ss(t1, _mm_set_ss(ray.tmax));
  lo = _mm_max_ss(_mm_shuffle_ps(t0, t0, _MM_SHUFFLE(3, 2, 0, 1)), lo);
  hi = _mm_min_ss(_mm_shuffle_ps(t1, t1, _MM_SHUFFLE(3, 2, 0, 1)), hi);
  lo = _mm_max_ss(_mm_movehl_ps(t0, t0), lo);
  hi = _mm_min_ss(_mm_movehl_ps(t1, t1), hi);
  const float t_entry = _mm_cvtss_f32(lo), t_exit = _mm_cvtss_f32(hi);
  if (!(t_entry <= t_exit)) return false;
  s->t_entry = t_entry;
  s->t_exit = t_exit;
  s->delta = _mm_cvtss_f32(delta);
  StoreBoxRay(o, inv, d, s);
  _mm_store_ps(s->tol, tol);
  // MakeWatertightRay's three divisions and the slack's one, in one. Its
  // axes come from WatertightAxes' branches, which the camera's and a
  // light's rays predict: a branch-free choice of the axes and lanes
  // (movemask, a table of pshufb controls) made the camera pass 1.4-2.4 %
  // longer and the render 0.7-2.2 % (render_bench, in one process, bunny,
  // city2 and teapots, 7 paired rounds; morse-buildings within noise),
  // and reading the frame's components from the stored vectors by index
  // instead of Vec3's selects made the camera pass 0.5-3 % longer.
  WatertightRay& w = s->wray;
  WatertightAxes(ray.dir, &w.kx, &w.ky, &w.kz);
  const int kz = w.kz;
  const float dz = ray.dir[kz];
  alignas(16) float depths[4], q[4];
  _mm_store_ps(depths, depth);
  _mm_store_ps(q, _mm_div_ps(_mm_setr_ps(ray.dir[w.kx], ray.dir[w.ky], 1.0f, depths[kz]),
                             _mm_setr_ps(dz, dz, dz, std::fabs(dz))));
  w.sx = q[0];
  w.sy = q[1];
  w.sz = q[2];
  s->slack = kHitSlack * q[3];
  w.ox = ray.origin[w.kx];
  w.oy = ray.origin[w.ky];
  w.oz = ray.origin[kz];
  w.origin = ray.origin;
  w.dir = ray.dir;
  return true;
}

}  // namespace ray_setup

// For a ray that passed SanitizeRay. Always inlined: GCC otherwise calls it
// from the closest-hit traversal, and its results go through memory (in one
// render_bench run, kd_origin, 7 paired rounds: inlined, T_R 1.028-1.039 on
// five of six scenes, dragon 1.003).
inline __attribute__((always_inline)) bool SetUpRay(const Ray& ray, const AABB& box,
                                                    RaySetup* s) {
  const __m128 d = _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 1.0f);
  if ((_mm_movemask_ps(_mm_cmpeq_ps(d, _mm_setzero_ps())) & 7) != 0) {
    return SetUpRayScalar(ray, box, s);
  }
  const __m128 o = _mm_setr_ps(ray.origin.x, ray.origin.y, ray.origin.z, 0.0f);
  return ray_setup::SetUpVector(o, d, ray, box, s);
}

// SanitizeRay (ray_check.h), then SetUpRay, for a ray as given: false for a
// ray SanitizeRay rejects or one that misses the box. The common ray (finite
// components, every direction component a normal float, tmin <= tmax), which
// SanitizeRay leaves as it is, is checked in one vector test and goes
// straight to the vector path; any other is sanitized in place and takes
// SetUpRay.
inline __attribute__((always_inline)) bool SanitizeAndSetUpRay(Ray* ray, const AABB& box,
                                                               RaySetup* s) {
  const __m128 d = _mm_setr_ps(ray->dir.x, ray->dir.y, ray->dir.z, 1.0f);
  const __m128 o = _mm_setr_ps(ray->origin.x, ray->origin.y, ray->origin.z, 0.0f);
  if (ray_setup::IsCommonRay(o, d, *ray)) return ray_setup::SetUpVector(o, d, *ray, box, s);
  return SanitizeRay(ray) && SetUpRay(*ray, box, s);
}

// What a box test needs of a common ray (above): s->org, s->inv and
// s->negative, as SetUpVector writes them (the same vector division); the
// other fields are left unset. False for any other ray, which then takes
// SanitizeAndSetUpRay. For a traversal whose boxes hold the scene and that
// needs the rest only at a leaf (leaf_bvh_traversal.cc's shadow rays): it
// skips the root box's interval and the watertight frame.
inline __attribute__((always_inline)) bool SetUpCommonBoxRay(const Ray& ray, RaySetup* s) {
  const __m128 d = _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 1.0f);
  const __m128 o = _mm_setr_ps(ray.origin.x, ray.origin.y, ray.origin.z, 0.0f);
  if (!ray_setup::IsCommonRay(o, d, ray)) return false;
  ray_setup::StoreBoxRay(o, _mm_div_ps(_mm_set1_ps(1.0f), d), d, s);
  return true;
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RAY_SETUP_H_
