#include "cc/geometry/exact_triple.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

// d . ((p1 - p0) x (q1 - q0)) in 128-bit integers, for coordinates that are
// integers times 2^-10.
int IntTripleSign(const Vec3& d, const Vec3& p1, const Vec3& p0, const Vec3& q1, const Vec3& q0) {
  auto i = [](float x) { return static_cast<__int128>(std::ldexp(static_cast<double>(x), 10)); };
  const __int128 dx = i(d.x), dy = i(d.y), dz = i(d.z);
  const __int128 px = i(p1.x) - i(p0.x), py = i(p1.y) - i(p0.y), pz = i(p1.z) - i(p0.z);
  const __int128 qx = i(q1.x) - i(q0.x), qy = i(q1.y) - i(q0.y), qz = i(q1.z) - i(q0.z);
  const __int128 s = dx * (py * qz - pz * qy) + dy * (pz * qx - px * qz) + dz * (px * qy - py * qx);
  return s > 0 ? 1 : (s < 0 ? -1 : 0);
}

TEST(ExactTriple, SignMatchesIntegerArithmetic) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> big(-(1 << 23), 1 << 23), small(-3, 3);
  auto g = [&](int m) { return std::ldexp(static_cast<float>(m), -10); };
  int zeros = 0, wrong_in_double = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 p0(g(big(rng)), g(big(rng)), g(big(rng)));
    const Vec3 q0(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 p1(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 q1(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 d(g(big(rng)), g(big(rng)), g(big(rng)));
    if (k % 2 == 1) {  // nearly coplanar: d = (p1 - p0) + (q1 - q0) + a tiny nudge
      const Vec3 p = p1 - p0, q = q1 - q0;  // exact: coordinates below 2^14 in steps of 2^-10
      d = Vec3(p.x + q.x + g(small(rng)), p.y + q.y + g(small(rng)), p.z + q.z + g(small(rng)));
    }
    const int want = IntTripleSign(d, p1, p0, q1, q0);
    ASSERT_EQ(TripleSign(d, p1, p0, q1, q0), want) << "case " << k;
    zeros += want == 0;
    const double p[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
    const double q[3] = {double(q1.x) - q0.x, double(q1.y) - q0.y, double(q1.z) - q0.z};
    const double s = d.x * (p[1] * q[2] - p[2] * q[1]) + d.y * (p[2] * q[0] - p[0] * q[2]) +
                     d.z * (p[0] * q[1] - p[1] * q[0]);
    wrong_in_double += (s > 0 ? 1 : (s < 0 ? -1 : 0)) != want;
  }
  EXPECT_GT(zeros, 10);  // the exact zeros were really exercised
  EXPECT_GT(wrong_in_double, 0);  // and so were signs that plain double gets wrong
}

}  // namespace
}  // namespace kdtree
