// Pinhole camera: one primary ray through the centre of each pixel.
//
// Basis: forward = normalize(look_at - position), right = normalize(forward x
// up), true_up = right x forward. Pixel (x, y), row 0 at the top, maps to
//   sx = (2 (x + 0.5) / width - 1) tan(fov / 2) aspect,
//   sy = (1 - 2 (y + 0.5) / height) tan(fov / 2),     aspect = width / height,
// and the ray is origin = position, dir = normalize(forward + sx right + sy
// true_up), [tmin, tmax] = [0, inf): t is the distance from the eye. fov is
// the vertical full angle; for a square image it is also the horizontal one.
// (Whitted-style eye rays; e.g. Pharr, Jakob, Humphreys, "Physically Based
// Rendering", 3rd ed., section 6.2, "Projective camera models".)
#ifndef KDTREE_CC_RENDER_CAMERA_H_
#define KDTREE_CC_RENDER_CAMERA_H_

#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"
#include "cc/render/view.h"

namespace kdtree {

class Camera {
 public:
  // `spec` must be valid (View::Validate).
  Camera(const CameraSpec& spec, int width, int height);

  Ray PrimaryRay(int x, int y) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& forward() const { return forward_; }

 private:
  Vec3 eye_, forward_, right_, up_;
  float half_w_, half_h_;
  int width_, height_;
};

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_CAMERA_H_
