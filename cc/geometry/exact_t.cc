#include "cc/geometry/exact_t.h"

#include "cc/geometry/exact_triple.h"
#include "cc/geometry/expansion.h"

namespace kdtree {
namespace {

// True when A . (B x C) is exactly zero because a column or a row of the
// matrix is: the origin lies in an axis-aligned plane that holds the whole
// triangle (a floor at y = 0 hit at a point computed on it exactly, which
// spawn.h leaves unmoved), or on a vertex. (A difference of two floats is zero
// in double exactly when they are equal.) The common hard case of shadow rays
// from such floors: the double filter cannot decide a zero.
bool TripleIsZero(const D3& A, const D3& B, const D3& C) {
  const bool column = (A.x == 0 && B.x == 0 && C.x == 0) || (A.y == 0 && B.y == 0 && C.y == 0) ||
                      (A.z == 0 && B.z == 0 && C.z == 0);
  const auto zero = [](const D3& v) { return v.x == 0 && v.y == 0 && v.z == 0; };
  return column || zero(A) || zero(B) || zero(C);
}

}  // namespace

namespace exact_t_internal {

bool ExactExpansions(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c,
                     float tmin) {
  using expansion::AddTo;
  using expansion::Diff;
  using expansion::Mul;
  using expansion::Sign;
  using expansion::Terms;
  using expansion::Triple;
  const Terms dt[3] = {{d.x}, {d.y}, {d.z}};
  const Terms A[3] = {Diff(a.x, o.x), Diff(a.y, o.y), Diff(a.z, o.z)};
  const Terms B[3] = {Diff(b.x, o.x), Diff(b.y, o.y), Diff(b.z, o.z)};
  const Terms C[3] = {Diff(c.x, o.x), Diff(c.y, o.y), Diff(c.z, o.z)};
  Terms det = Triple(dt, B, C);
  AddTo(Triple(dt, C, A), 1, &det);
  AddTo(Triple(dt, A, B), 1, &det);
  const int sdet = Sign(det);
  if (sdet == 0) return false;
  Terms lo = Triple(A, B, C);
  if (tmin != 0) AddTo(Mul(det, {static_cast<double>(tmin)}), -1, &lo);
  return Sign(lo) * sdet > 0;
}

}  // namespace exact_t_internal

bool ExactPlaneHitBeyond(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                         const Vec3& c, float tmin) {
  if (tmin == 0) {
    // Filter (the common case, a ray spawned from a surface): the signs of
    // A . (B x C) and of det = d . ((b - a) x (c - a)) in double, each
    // certified by its error bound. (The differences of the second are of
    // floats, exact in double apart from extreme exponent ranges, which the
    // bound covers as rounding of the differences.)
    const D3 A = Sub(a, o), B = Sub(b, o), C = Sub(c, o);
    if (TripleIsZero(A, B, C)) return false;  // t = 0 exactly (or no hit): not beyond 0
    const int snum = FilteredTriple(A, B, C);
    if (snum != 2) {
      const int sdet = FilteredTriple({d.x, d.y, d.z}, Sub(b, a), Sub(c, a));
      if (sdet != 2) return snum * sdet > 0;
    }
  }
  return exact_t_internal::ExactExpansions(o, d, a, b, c, tmin);
}

}  // namespace kdtree
