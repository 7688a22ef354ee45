// Exact ray-triangle predicates, to decide which of two tracers is right on a
// ray where they disagree (compare.h), and how close that ray passes to a
// triangle edge.
//
// The signs are exact (cc/geometry/expansion.h): every float input is a double, differences of two
// floats are kept exactly as two-term expansions (TwoSum), products as
// expansions (TwoProduct, with a correctly rounded fma), and the sum of all
// terms is formed as a nonoverlapping expansion (Grow-Expansion) whose largest
// component carries the sign. J. R. Shewchuk, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates", Discrete &
// Computational Geometry 18(3), 1997, sections 2.4-2.6. No overflow or
// underflow is assumed (|coordinates| between about 1e-30 and 1e30).
//
// With A = a - o, B = b - o, C = c - o (o the ray origin, d its direction):
//   U = d . (B x C), V = d . (C x A), W = d . (A x B)
// are the ray's signed sides of the edges bc, ca and ab; the ray's line meets
// the closed triangle exactly when they do not have strictly opposite signs
// and U + V + W = d . ((b - a) x (c - a)) is not zero; then the hit is at
// t = A . (B x C) / (U + V + W).
#ifndef KDTREE_CC_RENDER_EXACT_CHECK_H_
#define KDTREE_CC_RENDER_EXACT_CHECK_H_

#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

struct ExactTriangleHit {
  bool hit = false;  // exactly: the line meets the closed triangle, tmin < t <= tmax
  bool on_edge = false;  // exactly on an edge or vertex (one of U, V, W is 0)
  double t = 0;          // t of the hit (rounded; meaningful when the plane is not parallel)
  // Shortest distance between the ray's line and the lines of the triangle's
  // three edges (world units, rounded): how far the ray passes from the
  // nearest edge, measured across the ray, so a grazing angle does not hide a
  // close pass.
  double edge_distance = 0;
  // Distance from the ray origin to the triangle's plane (world units,
  // rounded): how far the origin is from the point where t changes sign.
  double plane_distance = 0;
  // max |coordinate| of the ray origin and the three vertices.
  double magnitude = 0;
};

// Exact classification of `ray` against triangle (a, b, c).
ExactTriangleHit ExactIntersect(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c);

// Units in the last place of a float of magnitude m: 2^(floor(log2 m) - 23).
double FloatUlp(double m);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_EXACT_CHECK_H_
