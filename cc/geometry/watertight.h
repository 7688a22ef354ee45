// Watertight ray-triangle intersection.
//
// Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection", Journal of
// Computer Graphics Techniques 2(1), 2013. Per ray: kz is the axis of the
// largest |dir| component, kx and ky the next two (swapped when dir[kz] < 0, so
// the winding is kept), and the shear S = (dir[kx] / dir[kz], dir[ky] /
// dir[kz], 1 / dir[kz]) maps the ray onto the +z axis through the origin. Per
// triangle, each vertex is translated by the ray origin and sheared:
//   X = A[kx] - Sx A[kz],  Y = A[ky] - Sy A[kz],  Z = Sz A[kz],
// and the three 2D edge functions
//   U = Cx By - Cy Bx,  V = Ax Cy - Ay Cx,  W = Bx Ay - By Ax
// decide the hit: inside when none is negative or none is positive (no
// back-face culling). A vertex shared by two triangles is transformed to the
// same floats in both, and an edge function of a shared edge is evaluated on
// the same two points (exactly negated). But those floats are rounded: the
// sign of a float edge function can differ from the sign of the exact one,
// d . (C x B) / |d[kz]| for U with A = a - o (and cyclically for V, W), for a
// ray that passes within rounding of an edge. So each float edge function is
// trusted only beyond a bound on its error (EdgeErrorBound below); one within
// it has its sign decided exactly (exact_triple.h: a double filter, then
// Shewchuk's expansions), in the manner of Shewchuk's adaptive predicates.
// Every sign the test acts on is then the exact sign for the ray as given,
// so the test is watertight (a shared edge's two signs are exact negations)
// and agrees with exact arithmetic on every ray: the hit is reported exactly
// when the ray's line meets the closed triangle within the t range
// (cc/render/exact_check.h).
// (Woop et al.'s own fallback, the edge function recomputed in double from the
// rounded sheared floats, is watertight but not exact.)
//
// Hit distance t = (U Az + V Bz + W Cz) / (U + V + W), evaluated in double once
// the signs agree; barycentrics u = V / det (weight of b) and v = W / det
// (weight of c), as in Hit. The t range is tmin < t <= tmax, inclusive at tmax
// like IntersectTriangle so that ties are broken by Closer(). A triangle of
// exactly zero area is never hit: when U + V + W is within rounding of zero the
// exact test of exact_area.h decides (the shear could otherwise round collinear
// vertices apart into a hittable sliver). And t > tmin must be right where
// rounding could get it wrong: when the triangle spans the origin's depth and
// t is within the bound on its rounding error (Pharr, Jakob & Humphreys,
// "Physically Based Rendering", 3rd ed., 2016, section 3.9.6) of tmin, the
// sign of t - tmin is decided in exact arithmetic (exact_t.h). So a ray
// leaving a surface never hits that surface again (spawn.h puts its origin on
// the right side exactly), and a real occluder close to the origin is never
// skipped (pbrt rejects every hit below the bound, which is loose for large or
// sliver triangles and lost real occluders). When all three vertices are
// clearly in front of the origin, t > 0 for sure and the bound is skipped;
// when all three are behind it (the sign of a vertex's depth is exact), no t
// > tmin >= 0 exists and the triangle is rejected before any of this.
//
// Requires -ffp-contract=off (set in .bazelrc): a fused multiply-add would
// break the exact negation of shared edge functions.
#ifndef KDTREE_CC_GEOMETRY_WATERTIGHT_H_
#define KDTREE_CC_GEOMETRY_WATERTIGHT_H_

#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "cc/geometry/exact_area.h"
#include "cc/geometry/exact_t.h"
#include "cc/geometry/float_bits.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// The per-ray part of the test: axis permutation, origin in permuted order,
// and shear.
struct WatertightRay {
  int kx, ky, kz;
  float ox, oy, oz;  // origin[kx], origin[ky], origin[kz]
  float sx, sy, sz;
  Vec3 origin, dir;  // the ray as given, for the exact t test (exact_t.h)
};

namespace watertight_internal {
// Component k of v (an indexed load, no temporary array).
inline float Component(const Vec3& v, int k) {
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
  float f[3];
  std::memcpy(f, &v, sizeof(f));
  return f[k];
}
}  // namespace watertight_internal

// `ray` must have a nonzero, finite direction (see SanitizeRay in ray_check.h).
// The axes of the watertight frame for direction d: kz the largest |d|
// component (ties go to the lower axis), kx and ky the next two cyclically,
// swapped when d[kz] < 0 to keep the winding.
inline void WatertightAxes(const Vec3& d, int* kx, int* ky, int* kz) {
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  *kz = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
  *kx = *kz == 2 ? 0 : *kz + 1;
  *ky = *kx == 2 ? 0 : *kx + 1;
  if (d[*kz] < 0.0f) std::swap(*kx, *ky);
}

inline WatertightRay MakeWatertightRay(const Ray& ray) {
  WatertightRay w;
  const float d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
  WatertightAxes(ray.dir, &w.kx, &w.ky, &w.kz);
  w.sx = d[w.kx] / d[w.kz];
  w.sy = d[w.ky] / d[w.kz];
  w.sz = 1.0f / d[w.kz];
  w.ox = ray.origin[w.kx];
  w.oy = ray.origin[w.ky];
  w.oz = ray.origin[w.kz];
  w.origin = ray.origin;
  w.dir = ray.dir;
  return w;
}

namespace watertight_internal {

// Sign test, degeneracy, t range and the conservative t > 0 bound. Reached
// only when the edge functions agree in sign (a hit in 2D), so it runs in
// double: det, T and t = T / det neither overflow nor lose precision for
// |coordinates| < 1e30.
inline bool Finish(const WatertightRay& r, double e0, double e1, double e2, const float x[3],
                   const float y[3], const float z[3], float max_abs_kz, const Vec3& a,
                   const Vec3& b, const Vec3& c, float tmin, float tmax, float* t, float* u,
                   float* v) {
  if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
  const double det = e0 + e1 + e2;
  if (det == 0) return false;  // the ray lies in the triangle's plane, or degenerate
  const double big_t = e0 * z[0] + e1 * z[1] + e2 * z[2];
  const double inv_det = 1.0 / det;
  float tt = static_cast<float>(big_t * inv_det);
  if (!(tt <= tmax && tt < std::numeric_limits<float>::infinity())) return false;
  // Bounds on the rounding of the sheared coordinates and of the edge
  // functions (PBRT 3rd ed. 3.9.6).
  const double max_x = FMax(std::fabs(x[0]), FMax(std::fabs(x[1]), std::fabs(x[2])));
  const double max_y = FMax(std::fabs(y[0]), FMax(std::fabs(y[1]), std::fabs(y[2])));
  const double max_z = FMax(std::fabs(z[0]), FMax(std::fabs(z[1]), std::fabs(z[2])));
  const double delta_x = Gamma(5) * (max_x + max_abs_kz);
  const double delta_y = Gamma(5) * (max_y + max_abs_kz);
  const double delta_e = 2 * (Gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  // A projected area within rounding of zero may come from a triangle of zero
  // area (collinear vertices, sheared apart by rounding): never hit those.
  if (std::fabs(det) <= 3 * delta_e && HasZeroArea(a, b, c)) return false;
  // t > tmin must be right. t is a convex combination of the vertex depths z
  // (the edge functions share a sign), so t > 0 for sure when every vertex is
  // in front of the origin by more than the rounding of z. Otherwise (the
  // triangle spans the origin's depth, as the one a ray was just spawned from
  // always does) t is compared with tmin outside the bound on its rounding
  // error (PBRT 3rd ed. 3.9.6), and decided exactly inside it.
  const double delta_z = Gamma(3) * max_z;
  if (FMin(z[0], FMin(z[1], z[2])) > delta_z) {
    if (!(tt > tmin)) return false;
  } else {
    const double max_e = FMax(std::fabs(e0), FMax(std::fabs(e1), std::fabs(e2)));
    const double delta_t =
        3 * (Gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * std::fabs(inv_det);
    if (double(tt) <= tmin - delta_t) return false;
    if (!(double(tt) > tmin + delta_t)) {
      // Within rounding of tmin: decide exactly. (The bound is loose for large
      // or sliver triangles, so rejecting here would lose real occluders.)
      if (!ExactPlaneHitBeyond(r.origin, r.dir, a, b, c, tmin)) return false;
      if (!(tt > tmin)) tt = std::nextafter(tmin, std::numeric_limits<float>::infinity());
    }
  }
  *t = tt;
  *u = static_cast<float>(e1 * inv_det);
  *v = static_cast<float>(e2 * inv_det);
  return true;
}

}  // namespace watertight_internal

namespace watertight_internal {

// The triangle in the ray's sheared frame, in floats: vertices relative to the
// origin, permuted and sheared (x, y), their depth before the 1 / d[kz] scale
// (dz = v[kz] - o[kz]), and the edge functions e = (U, V, W).
struct Sheared {
  float x[3], y[3], dz[3], e[3];
};

inline Sheared Shear(const WatertightRay& r, const Vec3& a, const Vec3& b, const Vec3& c) {
  Sheared s;
  s.dz[0] = Component(a, r.kz) - r.oz;
  s.dz[1] = Component(b, r.kz) - r.oz;
  s.dz[2] = Component(c, r.kz) - r.oz;
  s.x[0] = (Component(a, r.kx) - r.ox) - r.sx * s.dz[0];
  s.x[1] = (Component(b, r.kx) - r.ox) - r.sx * s.dz[1];
  s.x[2] = (Component(c, r.kx) - r.ox) - r.sx * s.dz[2];
  s.y[0] = (Component(a, r.ky) - r.oy) - r.sy * s.dz[0];
  s.y[1] = (Component(b, r.ky) - r.oy) - r.sy * s.dz[1];
  s.y[2] = (Component(c, r.ky) - r.oy) - r.sy * s.dz[2];
  s.e[0] = s.x[2] * s.y[1] - s.y[2] * s.x[1];  // U: edge b-c, weight of a
  s.e[1] = s.x[0] * s.y[2] - s.y[0] * s.x[2];  // V: edge c-a, weight of b
  s.e[2] = s.x[1] * s.y[0] - s.y[1] * s.x[0];  // W: edge a-b, weight of c
  return s;
}

// The constants of EdgeErrorBound (float, u = 2^-24).
inline constexpr float kEdgeBoundRel = 0x1p-19f;        // 32 u
inline constexpr float kEdgeBoundMinShear = 0x1p-31f;   // covers an underflowing shear
inline constexpr float kEdgeBoundMinDepth = 0x1p-90f;   // covers underflow in x, y
inline constexpr float kEdgeBoundAbs = 0x1p-146f;       // covers underflow in e

// The weight of the depth in the error of the sheared coordinates, per ray:
// max(|sx|, 2^-31) + max(|sy|, 2^-31).
inline float ShearWeight(const WatertightRay& r) {
  return FMax(std::fabs(r.sx), kEdgeBoundMinShear) + FMax(std::fabs(r.sy), kEdgeBoundMinShear);
}

// A bound on |e - E| for every edge function of Shear, E the exact edge
// function of the ray as given and the triangle's float vertices, from
// l = max(|x|, |y|) and mz = max |dz| over the three vertices and the ray's
// shear weight w = wx + wy (wx = max(|sx|, 2^-31), wy likewise). Each float
// operation rounds by at most u |result| + eta (u = 2^-24, eta = 2^-150 for
// underflow), the shear sx = d[kx] / d[kz] too (|sx| <= 1). So, with
// mx = max |x| and my = max |y|,
//   |x - X| <= gamma(4) (|x| + 2 wx |dz|) + 2 eta = Ex (the same for y, Ey),
//   |e - E| <= 4 u mx my + 2 (Ex my + mx Ey + Ex Ey) + 2 eta
//           <= u (20 mx my + 16 mz (wx my + wy mx)) + 4 eta (1 + mx + my)
// up to second-order terms, and mx my + mz (wx my + wy mx) <= l (l + mz w).
// The depth enters through the shear only, so a ray nearly parallel to a
// triangle's plane keeps a tight bound. 32 u l (l + (mz + 2^-90) w) + 2^-146
// covers all of it with room for its own float evaluation (each term's
// rounding, relative or by underflow, stays within the slack). An overflow
// makes the bound +inf or NaN, and then no edge function is trusted.
// The lane test's ShearLanes and RejectRays (cc/kdtree/lane_test-inl.h) do
// the same operations in the same order.
inline float EdgeErrorBound(float l, float mz, float w) {
  return kEdgeBoundRel * (l * (l + (mz + kEdgeBoundMinDepth) * w)) + kEdgeBoundAbs;
}

inline float MaxAbs3(const float v[3]) {
  return FMax(FMax(std::fabs(v[0]), std::fabs(v[1])), std::fabs(v[2]));
}

inline float EdgeErrorBound(const WatertightRay& r, const Sheared& s) {
  return EdgeErrorBound(FMax(MaxAbs3(s.x), MaxAbs3(s.y)), MaxAbs3(s.dz), ShearWeight(r));
}

// True when the edge functions have certainly different exact signs: one
// beyond +bound, one beyond -bound. (False for NaN.)
inline bool SignsDisagree(const float e[3], float bound) {
  return (e[0] < -bound || e[1] < -bound || e[2] < -bound) &&
         (e[0] > bound || e[1] > bound || e[2] > bound);
}

// True when every edge function's float sign is its exact sign.
inline bool SignsDecided(const float e[3], float bound) {
  return std::fabs(e[0]) > bound && std::fabs(e[1]) > bound && std::fabs(e[2]) > bound;
}

// The rest of the test when an edge function is within its error bound: its
// sign is decided exactly, then the signs are tested and Finish runs on the
// double edge functions, each set to 0 where its sign is not the exact one
// (watertight.cc).
bool FinishUndecided(const WatertightRay& r, const Sheared& s, float bound, const float z[3],
                     float max_abs_kz, const Vec3& a, const Vec3& b, const Vec3& c, float tmin,
                     float tmax, float* t, float* u, float* v);

}  // namespace watertight_internal

// Returns true and sets *t, *u, *v when the ray hits triangle (a, b, c) with
// tmin < t <= tmax (and t above its rounding-error bound). Edges and vertices
// are inclusive; a ray in the triangle's plane misses, and so does every ray
// for a triangle of exactly zero area (exact_area.h).
inline bool IntersectTriangleWatertight(const WatertightRay& r, const Vec3& a, const Vec3& b,
                                        const Vec3& c, float tmin, float tmax, float* t,
                                        float* u, float* v) {
  using namespace watertight_internal;  // NOLINT: the pieces of this test
  const Sheared s = Shear(r, a, b, c);
  const float bound = EdgeErrorBound(r, s);
  // A certain sign disagreement is a miss (the common case).
  if (SignsDisagree(s.e, bound)) return false;
  const float z[3] = {r.sz * s.dz[0], r.sz * s.dz[1], r.sz * s.dz[2]};
  // Every vertex behind the origin: z = sz (v[kz] - o[kz]) is its depth t
  // along the ray with a relative rounding error only, so its sign is exact,
  // and every point of the triangle lies at a convex combination of the
  // vertex depths, below 0: no hit with t > tmin >= 0. The line of a
  // secondary ray crosses such triangles behind its origin (0.8 per shadow
  // ray on city2); this spares them the double-precision Finish.
  if (tmin >= 0.0f && z[0] < 0.0f && z[1] < 0.0f && z[2] < 0.0f) return false;
  const float max_abs_kz = MaxAbs3(s.dz);
  if (!SignsDecided(s.e, bound)) {
    return FinishUndecided(r, s, bound, z, max_abs_kz, a, b, c, tmin, tmax, t, u, v);
  }
  return Finish(r, s.e[0], s.e[1], s.e[2], s.x, s.y, z, max_abs_kz, a, b, c, tmin, tmax, t, u, v);
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_WATERTIGHT_H_
