#include "cc/geometry/exact_t.h"

#include "cc/geometry/expansion.h"

namespace kdtree {

bool ExactPlaneHitBeyond(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                         const Vec3& c, float tmin) {
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

}  // namespace kdtree
