#include "cc/geometry/exact_triple.h"

#include <cmath>
#include <limits>

#include "cc/geometry/expansion.h"

namespace kdtree {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
constexpr double kErrBound = (7.0 + 56.0 * kEps) * kEps;              // Shewchuk's o3derrboundA

}  // namespace

int FilteredTriple(const D3& u, const D3& v, const D3& w) {
  const double vw_x = v.y * w.z - v.z * w.y, vw_y = v.z * w.x - v.x * w.z,
               vw_z = v.x * w.y - v.y * w.x;
  const double det = u.x * vw_x + u.y * vw_y + u.z * vw_z;
  const double perm = std::fabs(u.x) * (std::fabs(v.y * w.z) + std::fabs(v.z * w.y)) +
                      std::fabs(u.y) * (std::fabs(v.z * w.x) + std::fabs(v.x * w.z)) +
                      std::fabs(u.z) * (std::fabs(v.x * w.y) + std::fabs(v.y * w.x));
  if (std::fabs(det) > kErrBound * perm) return det > 0 ? 1 : -1;
  // Every product exactly 0 (no product of floats' differences underflows a
  // double): the determinant is exactly 0. The common exact zero: an
  // axis-aligned ray in an axis-aligned plane (the flat scenes' grazing
  // rays), decided here without the expansions.
  if (perm == 0) return 0;
  return 2;
}

namespace {

// The exact sign of d . (P x Q) for P, Q held exactly in doubles: each of the
// six products d[i] P[j] Q[k] is exactly four doubles (TwoProduct through a
// correctly rounded fma, twice), summed by expansion::SignInPlace without a
// heap allocation. Components of d that are 0 (axis-aligned rays) drop out.
int ExactTripleOfDoubles(const double d[3], const double P[3], const double Q[3]) {
  double terms[24];
  int n = 0;
  auto add = [&](double di, double pj, double qk, double sign) {
    const double h = pj * qk, l = std::fma(pj, qk, -h);
    const double hh = di * h, hl = std::fma(di, h, -hh);
    const double lh = di * l, ll = std::fma(di, l, -lh);
    terms[n++] = sign * hh;
    terms[n++] = sign * hl;
    terms[n++] = sign * lh;
    terms[n++] = sign * ll;
  };
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) continue;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    add(d[i], P[j], Q[k], 1);
    add(d[i], P[k], Q[j], -1);
  }
  return expansion::SignInPlace(terms, n);
}

// p - q in double, and whether that difference is exact.
bool ExactDiff(float p, float q, double* out) {
  double x, y;
  expansion::TwoSum(p, -static_cast<double>(q), &x, &y);
  *out = x;
  return y == 0;
}

}  // namespace

int TripleSign(const Vec3& d, const Vec3& p1, const Vec3& p0, const Vec3& q1, const Vec3& q0) {
  const int filtered = FilteredTriple({d.x, d.y, d.z}, Sub(p1, p0), Sub(q1, q0));
  if (filtered != 2) return filtered;
  // The differences of floats are exact in double unless their exponents lie
  // far apart; then the general expansions below.
  const double dd[3] = {d.x, d.y, d.z};
  double P[3], Q[3];
  if (ExactDiff(p1.x, p0.x, &P[0]) && ExactDiff(p1.y, p0.y, &P[1]) &&
      ExactDiff(p1.z, p0.z, &P[2]) && ExactDiff(q1.x, q0.x, &Q[0]) &&
      ExactDiff(q1.y, q0.y, &Q[1]) && ExactDiff(q1.z, q0.z, &Q[2])) {
    return ExactTripleOfDoubles(dd, P, Q);
  }
  using expansion::Diff;
  using expansion::Terms;
  const Terms dt[3] = {{d.x}, {d.y}, {d.z}};
  const Terms p[3] = {Diff(p1.x, p0.x), Diff(p1.y, p0.y), Diff(p1.z, p0.z)};
  const Terms q[3] = {Diff(q1.x, q0.x), Diff(q1.y, q0.y), Diff(q1.z, q0.z)};
  return expansion::Sign(expansion::Triple(dt, p, q));
}

}  // namespace kdtree
