#include "cc/kdtree/perfect_split.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kdtree {
namespace {

struct P3 {
  double v[3];
};

// Keeps the part of polygon `in` (n vertices) with sign * (x_axis - bound) <= 0.
int ClipPlane(const P3* in, int n, int axis, double bound, double sign, P3* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const P3& p = in[i];
    const P3& q = in[(i + 1) % n];
    const double dp = sign * (p.v[axis] - bound), dq = sign * (q.v[axis] - bound);
    if (dp <= 0) out[m++] = p;
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
      const double t = dp / (dp - dq);
      P3 r;
      for (int k = 0; k < 3; ++k) r.v[k] = p.v[k] + (q.v[k] - p.v[k]) * t;
      r.v[axis] = bound;
      out[m++] = r;
    }
  }
  return m;
}

float Down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -INFINITY);
  return f;
}
float Up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, INFINITY);
  return f;
}

}  // namespace

bool ClipTriangleToBox(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box, AABB* out) {
  if (!box.Valid()) return false;
  // A triangle clipped by 6 planes has at most 9 vertices.
  P3 poly[2][12] = {};
  const Vec3* v[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) poly[0][i] = P3{{v[i]->x, v[i]->y, v[i]->z}};
  int n = 3, cur = 0;
  // Grown by 1e-6 of the box's extent, plus the rounding of the cut points at
  // the coordinates' magnitude: the tree does not depend on where the scene
  // sits (issue 24).
  double size = 0, magnitude = 0;
  for (int k = 0; k < 3; ++k) {
    size = std::max(size, double(box.hi[k]) - double(box.lo[k]));
    magnitude = std::max({magnitude, std::abs(double(box.lo[k])), std::abs(double(box.hi[k])),
                          std::abs(double(a[k])), std::abs(double(b[k])), std::abs(double(c[k]))});
  }
  const double pad = size * 1e-6 + 16 * std::numeric_limits<double>::epsilon() * magnitude;
  for (int k = 0; k < 3 && n > 0; ++k) {
    n = ClipPlane(poly[cur], n, k, double(box.lo[k]) - pad, -1.0, poly[1 - cur]);
    cur = 1 - cur;
    if (n == 0) break;
    n = ClipPlane(poly[cur], n, k, double(box.hi[k]) + pad, 1.0, poly[1 - cur]);
    cur = 1 - cur;
  }
  if (n == 0) return false;
  AABB r;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      r.lo[k] = std::min(r.lo[k], Down(poly[cur][i].v[k]));
      r.hi[k] = std::max(r.hi[k], Up(poly[cur][i].v[k]));
    }
  }
  r = Intersect(r, box);
  if (!r.Valid()) return false;
  *out = r;
  return true;
}

}  // namespace kdtree
