// Exact arithmetic on sums of doubles, for predicates whose sign must be
// right: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", Discrete & Computational Geometry 18(3), 1997,
// sections 2.4-2.6.
//
// A value is a list of double terms whose exact sum it is (`Terms`, not kept
// nonoverlapping): the difference of two floats is two terms (TwoSum), a
// product of term lists is every pairwise product as TwoProduct (rounded
// product plus its exact remainder through a correctly rounded fma). `Sign`
// forms the nonoverlapping expansion (Grow-Expansion) and returns the sign of
// its largest component, which is the sign of the whole. No overflow or
// underflow is assumed (|coordinates| between about 1e-30 and 1e30). Slow
// (heap-allocated lists): for the rare cases that rounding cannot decide.
#ifndef KDTREE_CC_GEOMETRY_EXPANSION_H_
#define KDTREE_CC_GEOMETRY_EXPANSION_H_

#include <cmath>
#include <vector>

namespace kdtree {
namespace expansion {

// Shewchuk 1997, Theorem 7 (TwoSum): x + y == a + b exactly.
inline void TwoSum(double a, double b, double* x, double* y) {
  *x = a + b;
  const double bv = *x - a;
  const double av = *x - bv;
  *y = (a - av) + (b - bv);
}

// An exact value as a list of double terms.
using Terms = std::vector<double>;

// The exact difference of two floats as two terms.
inline Terms Diff(float p, float q) {
  double x, y;
  TwoSum(p, -static_cast<double>(q), &x, &y);
  return {x, y};
}

// Exact product of two term lists.
inline Terms Mul(const Terms& p, const Terms& q) {
  Terms out;
  out.reserve(2 * p.size() * q.size());
  for (double a : p) {
    for (double b : q) {
      const double x = a * b;
      out.push_back(x);
      out.push_back(std::fma(a, b, -x));
    }
  }
  return out;
}

// *sum += sign * p (sign is +1 or -1: exact).
inline void AddTo(const Terms& p, double sign, Terms* sum) {
  for (double x : p) sum->push_back(sign * x);
}

// Sign (-1, 0, 1) of the exact sum of the n doubles at `terms`, which it
// overwrites: Grow-Expansion (Theorem 10) with zero elimination, in place
// (the expansion so far occupies the front of the array, and each grown term
// is written at an index no greater than the one it was read from).
inline int SignInPlace(double* terms, int n) {
  int len = 0;  // terms[0, len) is the nonoverlapping expansion so far
  for (int i = 0; i < n; ++i) {
    double q = terms[i];
    if (q == 0) continue;
    int h = 0;
    for (int j = 0; j < len; ++j) {
      double sum, r;
      TwoSum(q, terms[j], &sum, &r);
      if (r != 0) terms[h++] = r;
      q = sum;
    }
    if (q != 0) terms[h++] = q;
    len = h;
  }
  if (len == 0) return 0;
  return terms[len - 1] > 0 ? 1 : -1;
}

// Sign (-1, 0, 1) of the exact sum of `terms`.
inline int Sign(Terms terms) { return SignInPlace(terms.data(), static_cast<int>(terms.size())); }

// d . (p x q) with d, p, q given as exact per-axis term lists.
inline Terms Triple(const Terms d[3], const Terms p[3], const Terms q[3]) {
  Terms sum;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    AddTo(Mul(d[i], Mul(p[j], q[k])), 1, &sum);
    AddTo(Mul(d[i], Mul(p[k], q[j])), -1, &sum);
  }
  return sum;
}

}  // namespace expansion
}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_EXPANSION_H_
