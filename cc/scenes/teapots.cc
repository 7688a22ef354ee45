#include "cc/scenes/teapots.h"

#include <algorithm>
#include <cmath>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

// `instance` rotated to y-up, centred on the y axis, bottom at y = 0, largest
// extent 1.
Mesh Normalised(const Mesh& instance, int up_axis) {
  Mesh m;
  m.Append(instance, up_axis == 2 ? Mat3::Rotation(0, -kPi / 2) : Mat3(), Vec3(0, 0, 0));
  const AABB box = m.Bounds();
  const Vec3 e = box.Extent();
  const float largest = std::max(e.x, std::max(e.y, e.z));
  const float s = largest > 0 ? 1.0f / largest : 1.0f;
  const Vec3 shift(-(box.lo.x + box.hi.x) / 2, -box.lo.y, -(box.lo.z + box.hi.z) / 2);
  for (Vec3& p : m.vertices) p = (p + shift) * s;
  return m;
}

}  // namespace

Mesh GenerateTeapots(const TeapotsConfig& config, const Mesh& instance) {
  Mesh mesh;
  if (instance.faces.empty()) return mesh;
  const Mesh unit = Normalised(instance, config.input_up_axis);
  const int64_t per = static_cast<int64_t>(unit.faces.size());
  const int64_t count =
      std::max<int64_t>(1, (std::max<int64_t>(config.target_triangles - 2, 0) + per / 2) / per);
  const int64_t cols = static_cast<int64_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  const int64_t rows = (count + cols - 1) / cols;
  const float pitch = config.spacing;
  const float tilt = config.max_tilt_deg * kPi / 180.0f;
  mesh.vertices.reserve(static_cast<size_t>(count) * unit.vertices.size() + 4);
  mesh.faces.reserve(static_cast<size_t>(count * per + 2));

  Rng rng(Mix64(config.seed) ^ 0x546561706f7473ULL);  // "Teapots"
  for (int64_t k = 0; k < count; ++k) {
    const float scale = rng.Uniform(config.min_scale, config.max_scale);
    const float yaw = rng.Uniform(0, 2 * kPi);
    const float tilt_x = rng.Uniform(-tilt, tilt), tilt_z = rng.Uniform(-tilt, tilt);
    const float jitter_x = rng.Uniform(-0.1f, 0.1f), jitter_z = rng.Uniform(-0.1f, 0.1f);
    const Mat3 rotation = Mat3::Rotation(0, tilt_x) * Mat3::Rotation(2, tilt_z) *
                          Mat3::Rotation(1, yaw) * Mat3::Scale(scale);
    // Lift the tilted instance so that its lowest point touches the ground.
    float lowest = 0;
    bool first = true;
    for (const Vec3& p : unit.vertices) {
      const float y = (rotation * p).y;
      if (first || y < lowest) lowest = y;
      first = false;
    }
    const float x = (static_cast<float>(k % cols) - 0.5f * static_cast<float>(cols - 1) + jitter_x);
    const float z = (static_cast<float>(k / cols) - 0.5f * static_cast<float>(rows - 1) + jitter_z);
    mesh.Append(unit, rotation, Vec3(x * pitch, -lowest, z * pitch));
  }
  const float hx = 0.5f * static_cast<float>(cols + 1) * pitch;
  const float hz = 0.5f * static_cast<float>(rows + 1) * pitch;
  const int32_t a = mesh.AddVertex({-hx, 0, -hz}), b = mesh.AddVertex({-hx, 0, hz});
  const int32_t c = mesh.AddVertex({hx, 0, hz}), d = mesh.AddVertex({hx, 0, -hz});
  mesh.AddQuad(a, b, c, d);  // ground, facing +y
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
