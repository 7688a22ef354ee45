// Floating-point helpers for error bounds: the gamma(n) bound of n roundings
// and stepping to the adjacent float.
//
// Pharr, Jakob & Humphreys, "Physically Based Rendering: From Theory to
// Implementation", 3rd ed., 2016, section 3.9.1 ("Floating-point arithmetic"):
// with unit roundoff eps = 2^-24, n successive roundings of a float result
// (1 + d1)...(1 + dn) lie within 1 +- gamma(n), gamma(n) = n eps / (1 - n eps).
#ifndef KDTREE_CC_GEOMETRY_FLOAT_BITS_H_
#define KDTREE_CC_GEOMETRY_FLOAT_BITS_H_

#include <cmath>
#include <limits>

namespace kdtree {

inline constexpr float kUnitRoundoff = std::numeric_limits<float>::epsilon() * 0.5f;  // 2^-24

// gamma(n) = n eps / (1 - n eps), the relative error bound of n roundings.
inline constexpr float Gamma(int n) { return (n * kUnitRoundoff) / (1 - n * kUnitRoundoff); }

// The next float towards +infinity (-infinity); +-0 both step to the smallest
// denormal of the right sign, infinities and NaN are returned unchanged.
inline float NextFloatUp(float x) {
  return std::isinf(x) && x > 0 ? x : std::nextafter(x, INFINITY);
}
inline float NextFloatDown(float x) {
  return std::isinf(x) && x < 0 ? x : std::nextafter(x, -INFINITY);
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_FLOAT_BITS_H_
