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
// the same two points (exactly negated), so a ray through a shared edge or
// vertex always hits at least one of the triangles. Rounding can only turn the
// sign of a x b - c d into zero, never flip it, so an edge function that comes
// out 0 (or overflows) is recomputed in double, where the products of floats
// are exact: that is the paper's "double precision fallback".
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

// Returns true and sets *t, *u, *v when the ray hits triangle (a, b, c) with
// tmin < t <= tmax (and t above its rounding-error bound). Edges and vertices
// are inclusive; a ray in the triangle's plane misses, and so does every ray
// for a triangle of exactly zero area (exact_area.h).
inline bool IntersectTriangleWatertight(const WatertightRay& r, const Vec3& a, const Vec3& b,
                                        const Vec3& c, float tmin, float tmax, float* t,
                                        float* u, float* v) {
  using watertight_internal::Component;
  // Vertices relative to the origin, permuted: (x, y, z) = (kx, ky, kz).
  const float az = Component(a, r.kz) - r.oz, bz = Component(b, r.kz) - r.oz,
              cz = Component(c, r.kz) - r.oz;
  const float x[3] = {(Component(a, r.kx) - r.ox) - r.sx * az,
                      (Component(b, r.kx) - r.ox) - r.sx * bz,
                      (Component(c, r.kx) - r.ox) - r.sx * cz};
  const float y[3] = {(Component(a, r.ky) - r.oy) - r.sy * az,
                      (Component(b, r.ky) - r.oy) - r.sy * bz,
                      (Component(c, r.ky) - r.oy) - r.sy * cz};
  const float e0 = x[2] * y[1] - y[2] * x[1];  // U: edge b-c, weight of a
  const float e1 = x[0] * y[2] - y[0] * x[2];  // V: edge c-a, weight of b
  const float e2 = x[1] * y[0] - y[1] * x[0];  // W: edge a-b, weight of c
  // A definite sign disagreement is a miss (the common case). Nonzero float
  // signs are exact, also when a product overflowed to +-inf.
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) {
    return false;
  }
  const float z[3] = {r.sz * az, r.sz * bz, r.sz * cz};
  // Every vertex behind the origin: z = sz (v[kz] - o[kz]) is its depth t
  // along the ray with a relative rounding error only, so its sign is exact,
  // and every point of the triangle lies at a convex combination of the
  // vertex depths, below 0: no hit with t > tmin >= 0. The line of a
  // secondary ray crosses such triangles behind its origin (0.8 per shadow
  // ray on city2); this spares them the double-precision Finish.
  if (tmin >= 0.0f && z[0] < 0.0f && z[1] < 0.0f && z[2] < 0.0f) return false;
  const float max_abs_kz = FMax(std::fabs(az), FMax(std::fabs(bz), std::fabs(cz)));
  constexpr float kMax = std::numeric_limits<float>::max();
  if (e0 != 0.0f && e1 != 0.0f && e2 != 0.0f && std::fabs(e0) <= kMax && std::fabs(e1) <= kMax &&
      std::fabs(e2) <= kMax) {
    return watertight_internal::Finish(r, e0, e1, e2, x, y, z, max_abs_kz, a, b, c, tmin, tmax, t, u,
                                      v);
  }
  // Double fallback: a zero, infinite or NaN edge function is recomputed in
  // double, where products of two floats are exact and so are the signs.
  const double d0 = double(x[2]) * y[1] - double(y[2]) * x[1];
  const double d1 = double(x[0]) * y[2] - double(y[0]) * x[2];
  const double d2 = double(x[1]) * y[0] - double(y[1]) * x[0];
  return watertight_internal::Finish(r, d0, d1, d2, x, y, z, max_abs_kz, a, b, c, tmin, tmax, t, u, v);
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_WATERTIGHT_H_
