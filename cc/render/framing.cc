#include "cc/render/framing.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "absl/strings/str_cat.h"

namespace kdtree {
namespace {

// The double nearest to `x` printed with 6 significant digits ("%.6g").
double Round6(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", x);
  return std::strtod(text, nullptr);
}

Point3d Round6(const Point3d& p) { return {Round6(p[0]), Round6(p[1]), Round6(p[2])}; }

constexpr double kPi = 3.14159265358979323846;
// Degrees to radians as x * (pi / 180): the manifest's cameras were first
// computed this way, and the rounding above keeps them exactly reproducible.
double Radians(double degrees) { return degrees * (kPi / 180.0); }

}  // namespace

absl::StatusOr<Framing> ParseFraming(int up_axis, const std::string& framing) {
  if (up_axis != 1 && up_axis != 2) {
    return absl::InvalidArgumentError(absl::StrCat("up axis ", up_axis, ": want 1 (y) or 2 (z)"));
  }
  if (framing != "object" && framing != "landscape" && framing != "interior") {
    return absl::InvalidArgumentError(
        absl::StrCat("framing '", framing, "': want object, landscape or interior"));
  }
  return Framing{up_axis, framing != "object"};
}

FramedView FrameBounds(const Point3d& lo, const Point3d& hi, const Framing& framing) {
  Point3d c, up{0, 0, 0}, front{0, 0, 0};
  double diagonal2 = 0;
  for (int a = 0; a < 3; ++a) {
    c[a] = (lo[a] + hi[a]) / 2;
    diagonal2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  }
  const double r = std::fmax(1e-6, std::sqrt(diagonal2) / 2);
  up[framing.up_axis] = 1.0;
  if (framing.up_axis == 1) {
    front[2] = 1.0;
  } else {
    front[1] = -1.0;
  }
  const Point3d side{1.0, 0.0, 0.0};
  const double elev = Radians(framing.raised_35 ? 35 : 15);
  FramedView v;
  const double d = r / std::sin(Radians(v.fov_deg) / 2) * 1.05;
  Point3d position, light;
  for (int a = 0; a < 3; ++a) {
    const double direction = std::cos(elev) * front[a] + std::sin(elev) * up[a];
    position[a] = c[a] + d * direction;
    light[a] = c[a] + r * (0.5 * side[a] + 1.5 * up[a] + 1.0 * front[a]);
  }
  v.position = Round6(position);
  v.look_at = Round6(c);
  v.up = up;
  v.light = Round6(light);
  return v;
}

View AutoView(const AABB& bounds) {
  Point3d lo{-1, -1, -1}, hi{1, 1, 1};
  if (bounds.Valid()) {
    lo = {bounds.lo.x, bounds.lo.y, bounds.lo.z};
    hi = {bounds.hi.x, bounds.hi.y, bounds.hi.z};
  }
  const FramedView f = FrameBounds(lo, hi, Framing());
  const auto vec = [](const Point3d& p) {
    return Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
  };
  View view;
  view.camera.position = vec(f.position);
  view.camera.look_at = vec(f.look_at);
  view.camera.up = vec(f.up);
  view.camera.fov_deg = static_cast<float>(f.fov_deg);
  view.lights.push_back(PointLight{vec(f.light)});
  return view;
}

}  // namespace kdtree
