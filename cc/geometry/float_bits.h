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
#include <cstdint>
#include <cstring>
#include <limits>

namespace kdtree {

inline constexpr float kUnitRoundoff = std::numeric_limits<float>::epsilon() * 0.5f;  // 2^-24

// gamma(n) = n eps / (1 - n eps), the relative error bound of n roundings.
inline constexpr float Gamma(int n) { return (n * kUnitRoundoff) / (1 - n * kUnitRoundoff); }

// The next float towards +infinity (-infinity); +-0 both step to the smallest
// denormal of the right sign, infinities and NaN are returned unchanged
// (std::nextafter's answers, without the libm call: by the bit pattern).
inline float NextFloatUp(float x) {
  if (!(x < INFINITY)) return x;  // +inf, NaN
  if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  bits = x > 0.0f ? bits + 1 : bits - 1;
  std::memcpy(&x, &bits, sizeof(bits));
  return x;
}
inline float NextFloatDown(float x) {
  if (!(x > -INFINITY)) return x;  // -inf, NaN
  if (x == 0.0f) return -std::numeric_limits<float>::denorm_min();
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  bits = x > 0.0f ? bits - 1 : bits + 1;
  std::memcpy(&x, &bits, sizeof(bits));
  return x;
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_FLOAT_BITS_H_
