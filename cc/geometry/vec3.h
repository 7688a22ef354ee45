// 3-component float vector used everywhere in the project.
//
// float32 on purpose: the report's numbers were produced in float32 and the
// seed-compatible mode reproduces them bit for bit (no FMA contraction; see
// .bazelrc, and the seed-compatible mode's rules in README.md, "The kd-tree").
#ifndef KDTREE_CC_GEOMETRY_VEC3_H_
#define KDTREE_CC_GEOMETRY_VEC3_H_

#include <cmath>

namespace kdtree {

struct Vec3 {
  float x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

  // Component by axis index 0 (x), 1 (y), 2 (z).
  float operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  float& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }

  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
  bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
  bool operator!=(const Vec3& o) const { return !(*this == o); }
};

inline float Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline float Length(const Vec3& a) { return std::sqrt(Dot(a, a)); }

inline Vec3 Normalize(const Vec3& a) {
  const float len = Length(a);
  return len > 0 ? a / len : a;
}

// std::fmin / std::fmax (a NaN operand yields the other one), inline: GCC calls
// libm for them, a function call per box coordinate in the builders and
// several per watertight hit test. (Signed zeros may come out either way, as
// std::fmin / std::fmax allow; the callers compare or take magnitudes only.)
inline float FMin(float a, float b) { return (b < a || a != a) ? b : a; }
inline float FMax(float a, float b) { return (b > a || a != a) ? b : a; }
inline double FMin(double a, double b) { return (b < a || a != a) ? b : a; }
inline double FMax(double a, double b) { return (b > a || a != a) ? b : a; }

inline Vec3 Min(const Vec3& a, const Vec3& b) {
  return {FMin(a.x, b.x), FMin(a.y, b.y), FMin(a.z, b.z)};
}

inline Vec3 Max(const Vec3& a, const Vec3& b) {
  return {FMax(a.x, b.x), FMax(a.y, b.y), FMax(a.z, b.z)};
}

inline bool IsFinite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_VEC3_H_
