#include "cc/render/camera.h"

#include <cmath>

namespace kdtree {

Camera::Camera(const CameraSpec& spec, int width, int height)
    : eye_(spec.position), width_(width), height_(height) {
  forward_ = Normalize(spec.look_at - spec.position);
  right_ = Normalize(Cross(forward_, spec.up));
  up_ = Cross(right_, forward_);
  const double half = std::tan(static_cast<double>(spec.fov_deg) * 0.5 * 3.14159265358979323846 / 180.0);
  half_h_ = static_cast<float>(half);
  half_w_ = static_cast<float>(half * width / height);
}

Ray Camera::PrimaryRay(int x, int y) const {
  const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width_) - 1.0f) * half_w_;
  const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_)) * half_h_;
  Ray ray;
  ray.origin = eye_;
  ray.dir = Normalize(forward_ + right_ * sx + up_ * sy);
  return ray;
}

}  // namespace kdtree
