// The per-ray set-up of SetUpRay (ray_setup.h) for 4 rays at once, one ray
// per SSE lane, for the packet traversal (ray_packet.h): 3 + 4 divisions of 4
// lanes for the packet instead of 2 per ray, and every slab, tolerance and
// the root interval computed for the 4 rays together. Each lane performs the
// operations of SetUpRay's SSE path in the same order (MINPS / MAXPS pick
// what its comparisons pick; no contraction: -ffp-contract=off), so lane i
// holds exactly what SetUpRay writes for ray i (ray_setup_test.cc checks every
// field, bit for bit).
#ifndef KDTREE_CC_KDTREE_RAY_SETUP4_H_
#define KDTREE_CC_KDTREE_RAY_SETUP4_H_

#include <cmath>

#include "cc/geometry/aabb.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/ray_setup.h"

#include <immintrin.h>

namespace kdtree {

// RaySetup's fields with the lanes side by side ([axis][lane] for vectors).
struct RaySetup4 {
  alignas(16) float org[3][4];
  alignas(16) float inv[3][4];
  alignas(16) float tol[3][4];
  alignas(16) float t_entry[4];
  alignas(16) float t_exit[4];
  alignas(16) float slack[4];
  alignas(16) float delta[4];
  bool negative[4][3];  // [lane][axis]
  WatertightRay wray[4];
};

// Lane i of `s` from one ray's set-up.
inline void SetLane(const RaySetup& r, int i, RaySetup4* s) {
  for (int k = 0; k < 3; ++k) {
    s->org[k][i] = r.org[k];
    s->inv[k][i] = r.inv[k];
    s->tol[k][i] = r.tol[k];
    s->negative[i][k] = r.negative[k];
  }
  s->t_entry[i] = r.t_entry;
  s->t_exit[i] = r.t_exit;
  s->slack[i] = r.slack;
  s->delta[i] = r.delta;
  s->wray[i] = r.wray;
}

// rays[0..4) must have passed SanitizeRay (ray_check.h) and have no zero
// direction component (SetUpRay's SSE path). Returns bit i set when ray i
// reaches the padded box (SetUpRay returns true); the other lanes' fields are
// unspecified.
inline int SetUpRays4(const Ray* rays, const AABB& box, RaySetup4* s) {
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 one = _mm_set1_ps(1.0f), pad = _mm_set1_ps(ray_setup::kPad);
  __m128 dl[3], dh[3], inv[3], depth[3];
  __m128 reach = _mm_setzero_ps();
  for (int k = 0; k < 3; ++k) {
    const __m128 o =
        _mm_setr_ps(rays[0].origin[k], rays[1].origin[k], rays[2].origin[k], rays[3].origin[k]);
    const __m128 d = _mm_setr_ps(rays[0].dir[k], rays[1].dir[k], rays[2].dir[k], rays[3].dir[k]);
    _mm_store_ps(s->org[k], o);
    dl[k] = _mm_sub_ps(_mm_set1_ps(box.lo[k]), o);
    dh[k] = _mm_sub_ps(_mm_set1_ps(box.hi[k]), o);
    inv[k] = _mm_div_ps(one, d);
    _mm_store_ps(s->inv[k], inv[k]);
    // SetUpRay: reach = Max(reach, Max(|dl|, |dh|)) axis by axis, Max(a, b)
    // = a > b ? a : b = MAXPS(a, b).
    depth[k] = _mm_max_ps(_mm_and_ps(dl[k], abs_mask), _mm_and_ps(dh[k], abs_mask));
    reach = _mm_max_ps(reach, depth[k]);
  }
  const __m128 delta = _mm_mul_ps(_mm_set1_ps(ray_setup::kSpatialTol), reach);
  _mm_store_ps(s->delta, delta);
  __m128 lo = _mm_setr_ps(rays[0].tmin, rays[1].tmin, rays[2].tmin, rays[3].tmin);
  __m128 hi = _mm_setr_ps(rays[0].tmax, rays[1].tmax, rays[2].tmax, rays[3].tmax);
  for (int k = 0; k < 3; ++k) {
    const __m128 tol = _mm_mul_ps(delta, _mm_and_ps(inv[k], abs_mask));
    _mm_store_ps(s->tol[k], tol);
    const __m128 tn = _mm_mul_ps(dl[k], inv[k]), tf = _mm_mul_ps(dh[k], inv[k]);
    __m128 t0 = _mm_min_ps(tf, tn), t1 = _mm_max_ps(tn, tf);
    t0 = _mm_sub_ps(t0, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t0, abs_mask), pad), tol));
    t1 = _mm_add_ps(t1, _mm_add_ps(_mm_mul_ps(_mm_and_ps(t1, abs_mask), pad), tol));
    // SetUpRay: if (t0 > lo) lo = t0; if (t1 < hi) hi = t1.
    lo = _mm_max_ps(t0, lo);
    hi = _mm_min_ps(t1, hi);
  }
  const int live = _mm_movemask_ps(_mm_cmple_ps(lo, hi));
  _mm_store_ps(s->t_entry, lo);
  _mm_store_ps(s->t_exit, hi);
  // The watertight rays: per lane its axes, then the shears and the slack's
  // depth / |dir[kz]| as 4 divisions of 4 lanes.
  alignas(16) float depth_f[3][4];
  for (int k = 0; k < 3; ++k) _mm_store_ps(depth_f[k], depth[k]);
  alignas(16) float num_x[4], num_y[4], den[4], num_d[4], den_abs[4];
  for (int i = 0; i < 4; ++i) {
    WatertightRay& w = s->wray[i];
    const Ray& ray = rays[i];
    WatertightAxes(ray.dir, &w.kx, &w.ky, &w.kz);
    num_x[i] = ray.dir[w.kx];
    num_y[i] = ray.dir[w.ky];
    den[i] = ray.dir[w.kz];
    den_abs[i] = std::fabs(den[i]);
    num_d[i] = depth_f[w.kz][i];
    w.ox = ray.origin[w.kx];
    w.oy = ray.origin[w.ky];
    w.oz = ray.origin[w.kz];
    w.origin = ray.origin;
    w.dir = ray.dir;
    for (int k = 0; k < 3; ++k) s->negative[i][k] = std::signbit(ray.dir[k]);
  }
  const __m128 dz = _mm_load_ps(den);
  alignas(16) float sx[4], sy[4], sz[4], sd[4];
  _mm_store_ps(sx, _mm_div_ps(_mm_load_ps(num_x), dz));
  _mm_store_ps(sy, _mm_div_ps(_mm_load_ps(num_y), dz));
  _mm_store_ps(sz, _mm_div_ps(one, dz));
  _mm_store_ps(sd, _mm_div_ps(_mm_load_ps(num_d), _mm_load_ps(den_abs)));
  _mm_store_ps(s->slack, _mm_mul_ps(_mm_set1_ps(ray_setup::kHitSlack), _mm_load_ps(sd)));
  for (int i = 0; i < 4; ++i) {
    s->wray[i].sx = sx[i];
    s->wray[i].sy = sy[i];
    s->wray[i].sz = sz[i];
  }
  return live;
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RAY_SETUP4_H_
