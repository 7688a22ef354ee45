// Teapots: many instances of one input mesh (the Utah teapot) on a grid with
// random rotations and scales over a ground quad: stand-in for the report's
// scene 10 (teapots, 200,748 triangles). Instancing is flattened: every
// instance is a separate copy of the input's triangles.
#ifndef KDTREE_CC_SCENES_TEAPOTS_H_
#define KDTREE_CC_SCENES_TEAPOTS_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct TeapotsConfig {
  // Triangles wanted: round((target - 2) / instance triangles) instances (at
  // least one) plus 2 for the ground, so within half an instance of it.
  int64_t target_triangles = 200748;
  uint64_t seed = 1;
  // Grid pitch in units of the largest instance extent (scaled to 1).
  float spacing = 1.25f;
  // Uniform scale of each instance, drawn from [min_scale, max_scale).
  float min_scale = 0.6f;
  float max_scale = 1.2f;
  // Largest tilt about the horizontal axes, in degrees (yaw is free).
  float max_tilt_deg = 25.0f;
  // Axis of the input that points up: 1 (y) or 2 (z); output is y-up.
  int input_up_axis = 1;
};

// `instance` is centred and scaled so that its largest extent is 1, its
// bottom resting on y = 0 before the random tilt.
Mesh GenerateTeapots(const TeapotsConfig& config, const Mesh& instance);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_TEAPOTS_H_
