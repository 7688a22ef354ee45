// The default camera and light of a scene, from its bounds: the project's one
// framing rule. data/manifest.json's cameras are this rule applied to each
// scene's measured bounds (the auto_view tool prints it, and
// data/manifest_test.py checks every manifest camera against it); the tools
// use it for a mesh that has no manifest camera (AutoView).
//
// The bounding sphere (centre c, radius r = half the box's diagonal) fits a
// 45-degree view from the front, +z for y-up scenes and -y for z-up ones
// (Blender files), with a 5 % margin: the eye is at distance
// d = 1.05 r / sin(22.5 degrees) from c, raised 15 degrees above the centre for
// objects, 35 for landscapes and interiors. One point light above-front-right
// at c + r (0.5 side + 1.5 up + 1.0 front), side = +x. Computed in double;
// positions and the look-at point are rounded to 6 significant digits, as the
// manifest stores them.
#ifndef KDTREE_CC_RENDER_FRAMING_H_
#define KDTREE_CC_RENDER_FRAMING_H_

#include <array>
#include <string>

#include "absl/status/statusor.h"
#include "cc/geometry/aabb.h"
#include "cc/render/view.h"

namespace kdtree {

using Point3d = std::array<double, 3>;

struct Framing {
  int up_axis = 1;         // 1: y up; 2: z up
  bool raised_35 = false;  // landscapes and interiors; objects are raised 15 degrees
};

// "object" -> 15 degrees; "landscape" or "interior" -> 35 (the manifest's
// `framing`); an error names any other word.
absl::StatusOr<Framing> ParseFraming(int up_axis, const std::string& framing);

struct FramedView {
  Point3d position, look_at, up;
  double fov_deg = 45.0;
  Point3d light;
};

// The rule above for the box [lo, hi].
FramedView FrameBounds(const Point3d& lo, const Point3d& hi, const Framing& framing);

// FrameBounds for `bounds` (y up, an object) as a View of one light; the box
// [-1, 1]^3 when `bounds` is empty (no triangles: nothing to frame).
View AutoView(const AABB& bounds);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_FRAMING_H_
