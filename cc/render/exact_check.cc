#include "cc/render/exact_check.h"

#include "cc/geometry/expansion.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace kdtree {
namespace {

using expansion::AddTo;
using expansion::Diff;
using expansion::Mul;
using expansion::Sign;
using expansion::Terms;
using expansion::Triple;

using LD = long double;

struct V3 {
  LD x, y, z;
};
V3 Sub(const Vec3& p, const Vec3& q) { return {LD(p.x) - q.x, LD(p.y) - q.y, LD(p.z) - q.z}; }
V3 Cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
LD Dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LD Norm(const V3& a) { return std::sqrt(Dot(a, a)); }

// Distance between the line o + t d and the line through p and q.
double LineDistance(const Vec3& o, const Vec3& d, const Vec3& p, const Vec3& q) {
  const V3 dd{d.x, d.y, d.z};
  const V3 e = Sub(q, p);
  const V3 w = Sub(p, o);
  const V3 n = Cross(dd, e);
  const LD nn = Norm(n);
  if (nn > 0 && nn > 1e-12L * Norm(dd) * Norm(e)) return static_cast<double>(std::fabs(Dot(w, n)) / nn);
  // Parallel: distance from p to the ray's line.
  return static_cast<double>(Norm(Cross(w, dd)) / Norm(dd));
}

double MaxAbs(const Vec3& v) {
  return std::max({std::fabs(double(v.x)), std::fabs(double(v.y)), std::fabs(double(v.z))});
}

}  // namespace

double FloatUlp(double m) {
  if (!(m > 0)) return 0;
  int e;
  std::frexp(m, &e);  // m = f 2^e, f in [0.5, 1)
  return std::ldexp(1.0, e - 24);
}

ExactTriangleHit ExactIntersect(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  ExactTriangleHit out;
  const Vec3& o = ray.origin;
  out.magnitude = std::max({MaxAbs(o), MaxAbs(a), MaxAbs(b), MaxAbs(c)});
  out.edge_distance = std::min({LineDistance(o, ray.dir, b, c), LineDistance(o, ray.dir, c, a),
                                LineDistance(o, ray.dir, a, b)});
  const Terms d[3] = {{ray.dir.x}, {ray.dir.y}, {ray.dir.z}};
  const Terms A[3] = {Diff(a.x, o.x), Diff(a.y, o.y), Diff(a.z, o.z)};
  const Terms B[3] = {Diff(b.x, o.x), Diff(b.y, o.y), Diff(b.z, o.z)};
  const Terms C[3] = {Diff(c.x, o.x), Diff(c.y, o.y), Diff(c.z, o.z)};
  const Terms u = Triple(d, B, C), v = Triple(d, C, A), w = Triple(d, A, B);
  const int su = Sign(u), sv = Sign(v), sw = Sign(w);
  out.on_edge = su == 0 || sv == 0 || sw == 0;
  const bool inside = !((su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0));
  Terms det = u;
  AddTo(v, 1, &det);
  AddTo(w, 1, &det);
  const int sdet = Sign(det);
  const Terms num = Triple(A, B, C);  // A . (B x C)
  // Rounded t, for reports.
  const V3 dd{ray.dir.x, ray.dir.y, ray.dir.z};
  const V3 la = Sub(a, o), lb = Sub(b, o), lc = Sub(c, o);
  const V3 n = Cross(Sub(b, a), Sub(c, a));
  const LD ldet = Dot(dd, n);
  const LD lnum = Dot(la, Cross(lb, lc));
  out.t = ldet != 0 ? static_cast<double>(lnum / ldet) : 0.0;
  out.plane_distance = Norm(n) > 0 ? static_cast<double>(std::fabs(lnum) / Norm(n)) : 0.0;
  if (!inside || sdet == 0) return out;
  // tmin < t <= tmax, i.e. (num - tmin det) sdet > 0 and (tmax det - num) sdet >= 0.
  auto scaled = [&](float s) {
    Terms r = Mul(det, {static_cast<double>(s)});
    return r;
  };
  Terms lo = num;
  AddTo(scaled(ray.tmin), -1, &lo);
  if (Sign(lo) * sdet <= 0) return out;
  if (std::isfinite(ray.tmax)) {
    Terms hi = scaled(ray.tmax);
    AddTo(num, -1, &hi);
    if (Sign(hi) * sdet < 0) return out;
  }
  out.hit = true;
  return out;
}

}  // namespace kdtree
