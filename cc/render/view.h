// What to render: camera, image size, point lights, optional ambient occlusion.
//
// The report renders each scene from a `.view` file extended with a point
// light (its section "Results": files ending in `_L.view`). Its exact syntax is
// not printed, so this project uses its own small text format in the same
// spirit (same block style as the environment files):
//
//   # comments run from '#' or '//' to the end of the line
//   camera {
//     position 0.1 0.2 2.5     # eye point
//     look_at  0 0.1 0         # the image centre looks at this point
//     up       0 1 0           # optional, default 0 1 0
//     fov      45              # optional, default 45: vertical field of view
//   }                          #   in degrees (the full angle, 0 < fov < 180)
//   resolution 800 800         # optional, default 800 800 (width height)
//   light { position 1 2 3 }   # zero or more point lights
//   ambient_occlusion { samples 16 distance 0.05 }   # optional effect
//
// Tokens are separated by white space; '{' and '}' are tokens of their own
// even when written against a word. `camera` is required, once; inside a
// block each key may appear once (position and look_at required). Numbers
// must be finite. `distance` of ambient occlusion is in scene units. A view
// without any light renders with a headlight shading and traces no shadow
// rays. Errors name the file, the line and the reason.
#ifndef KDTREE_CC_RENDER_VIEW_H_
#define KDTREE_CC_RENDER_VIEW_H_

#include <cstddef>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/geometry/aabb.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

struct CameraSpec {
  Vec3 position;
  Vec3 look_at;
  Vec3 up{0, 1, 0};
  float fov_deg = 45.0f;  // vertical, full angle
};

struct PointLight {
  Vec3 position;
};

struct AmbientOcclusion {
  int samples = 0;        // rays per primary hit; 0 = effect off
  float distance = 0.0f;  // ray length in scene units
  bool enabled() const { return samples > 0; }
};

// The most lights a view may have: a ray record's light index
// (cc/render/ray_record.h, and the ray dump's) is 16 bits wide.
inline constexpr size_t kMaxLights = 65535;

struct View {
  CameraSpec camera;
  int width = 800;
  int height = 800;
  std::vector<PointLight> lights;
  AmbientOcclusion ao;

  // Camera not degenerate (eye != look_at, up not along the view direction),
  // 0 < fov < 180, 1 <= width, height <= 16384, at most kMaxLights lights, AO
  // samples in [0, 4096] with distance > 0 when on, everything finite. `where`
  // prefixes the message.
  absl::Status Validate(const std::string& where) const;
};

// Parses the format above; `filename` is used in error messages only.
absl::StatusOr<View> ParseView(const std::string& text, const std::string& filename);

// Reads and parses a view file.
absl::StatusOr<View> LoadViewFile(const std::string& path);

// The view in the format above (ParseView(ViewToText(v)) == v up to float
// printing, which uses %.9g and so round-trips exactly).
std::string ViewToText(const View& view);

// Whether rays in single precision can trace a scene of these bounds: its
// largest extent must lie in [kMinSceneExtent, kMaxSceneExtent] (the
// triangle tests multiply coordinate differences: below, products underflow
// and every ray misses; above, they overflow) and be at least
// kMinRelativeExtent of its largest coordinate's magnitude (else its
// vertices and the camera collapse onto few float values). Error: "the scene
// spans E ... " with the bound it breaks (issue 24: numeric extremes).
inline constexpr double kMinSceneExtent = 1e-15, kMaxSceneExtent = 1e15;
inline constexpr double kMinRelativeExtent = 1e-6;
absl::Status CheckSceneScale(const AABB& bounds);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_VIEW_H_
