#include "cc/geometry/spawn.h"

#include <cmath>

#include "cc/geometry/float_bits.h"

namespace kdtree {

namespace {
Vec3 Abs(const Vec3& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
}  // namespace

BoundedPoint HitPointWithError(const Vec3& a, const Vec3& b, const Vec3& c, float u, float v) {
  const Vec3 s1 = (b - a) * u;
  const Vec3 s2 = (c - a) * v;
  BoundedPoint out;
  out.p = (a + s1) + s2;
  out.error = (Abs(a) + Abs(s1) + Abs(s2)) * Gamma(6);
  return out;
}

Vec3 GeometricNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !std::isfinite(len)) return Vec3(0, 0, 0);
  return Vec3(static_cast<float>(n[0] / len), static_cast<float>(n[1] / len),
              static_cast<float>(n[2] / len));
}

Vec3 OffsetRayOrigin(const BoundedPoint& point, const Vec3& n, const Vec3& w) {
  const float d = Dot(Abs(n), point.error);
  Vec3 offset = n * d;
  if (Dot(w, n) < 0) offset = -offset;
  Vec3 po = point.p + offset;
  // Round away from p, so the rounding of the addition cannot undo the offset.
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) {
      po[i] = NextFloatUp(po[i]);
    } else if (offset[i] < 0) {
      po[i] = NextFloatDown(po[i]);
    }
  }
  return po;
}

Ray SpawnRay(const BoundedPoint& point, const Vec3& n, const Vec3& dir) {
  Ray ray;
  ray.origin = OffsetRayOrigin(point, n, dir);
  ray.dir = dir;
  return ray;
}

Ray SpawnShadowRay(const BoundedPoint& point, const Vec3& n, const Vec3& light) {
  Ray ray;
  ray.origin = OffsetRayOrigin(point, n, light - point.p);
  ray.dir = light - ray.origin;
  ray.tmin = 0.0f;
  ray.tmax = 1.0f;
  return ray;
}

}  // namespace kdtree
