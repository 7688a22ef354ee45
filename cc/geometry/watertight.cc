#include "cc/geometry/watertight.h"

#include "cc/geometry/exact_triple.h"

namespace kdtree {
namespace watertight_internal {

bool FinishUndecided(const WatertightRay& r, const Sheared& s, float bound, const float z[3],
                     float max_abs_kz, const Vec3& a, const Vec3& b, const Vec3& c, float tmin,
                     float tmax, float* t, float* u, float* v) {
  // A ray parallel to the triangle's plane (exactly) misses it; the float
  // edge functions of such a ray are all within rounding of 0, and grazing
  // rays of flat scenes meet many such triangles: one exact test for them.
  if (s.e[0] == 0 && s.e[1] == 0 && s.e[2] == 0 && TripleSign(r.dir, b, a, c, a) == 0) {
    return false;
  }
  // Exact signs: e[i] has the sign of d . (P x Q) with P = v[i + 2] - o and
  // Q = v[i + 1] - o (indices mod 3): U ~ d . (C x B), V ~ d . (A x C),
  // W ~ d . (B x A), each divided by |d[kz]| > 0.
  const Vec3* vert[3] = {&a, &b, &c};
  int sign[3];
  for (int i = 0; i < 3; ++i) {
    if (s.e[i] > bound) {
      sign[i] = 1;
    } else if (s.e[i] < -bound) {
      sign[i] = -1;
    } else {
      sign[i] = TripleSign(r.dir, *vert[(i + 2) % 3], r.origin, *vert[(i + 1) % 3], r.origin);
    }
  }
  const bool neg = sign[0] < 0 || sign[1] < 0 || sign[2] < 0;
  const bool pos = sign[0] > 0 || sign[1] > 0 || sign[2] > 0;
  if (neg == pos) return false;  // opposite signs (a miss), or all zero (in the plane)
  // Weights for t and the barycentrics: the edge functions of the sheared
  // floats in double (products of floats are exact), 0 where that sign is not
  // the exact one (they are then within rounding of 0); the exact signs
  // themselves if nothing is left.
  double e[3] = {double(s.x[2]) * s.y[1] - double(s.y[2]) * s.x[1],
                 double(s.x[0]) * s.y[2] - double(s.y[0]) * s.x[2],
                 double(s.x[1]) * s.y[0] - double(s.y[1]) * s.x[0]};
  for (int i = 0; i < 3; ++i) {
    if (!(e[i] * sign[i] > 0)) e[i] = 0;
  }
  if (e[0] == 0 && e[1] == 0 && e[2] == 0) {
    for (int i = 0; i < 3; ++i) e[i] = sign[i];
  }
  return Finish(r, e[0], e[1], e[2], s.x, s.y, z, max_abs_kz, a, b, c, tmin, tmax, t, u, v);
}

}  // namespace watertight_internal
}  // namespace kdtree
