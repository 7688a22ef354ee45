// Hairball: a tangle of thin tubes inside a ball (stand-in for the report's
// scene 12, 2,880,000 triangles), the worst case for spatial subdivision:
// long thin triangles in every orientation crossing each other everywhere.
#ifndef KDTREE_CC_SCENES_HAIRBALL_H_
#define KDTREE_CC_SCENES_HAIRBALL_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct HairballConfig {
  // Triangles wanted. The result has 2 * sides * round(target / (2 * sides))
  // triangles: within `sides` triangles of the target.
  int64_t target_triangles = 2880000;
  uint64_t seed = 1;
  // Segments around a tube (its cross-section is a `sides`-gon), >= 3.
  int sides = 4;
  // Segments along one tube (curve steps); the last tube may be shorter.
  int segments_per_tube = 200;
  // Radius of the ball the curves stay in (they may overshoot a little).
  float ball_radius = 1.0f;
  // Length of one curve step, in ball radii.
  float step = 0.01f;
  // Tube radius in ball radii; 0 picks 0.0025 * sqrt(2,880,000 / target)
  // (at most 0.03) so that small hairballs still look like hair.
  float tube_radius = 0.0f;
  // How fast a curve turns (radians per step, random walk of the turn rate).
  float curl = 0.12f;
};

// Open tubes (no caps) along smooth random curves; vertices are shared along a
// tube, tubes are separate.
Mesh GenerateHairball(const HairballConfig& config);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_HAIRBALL_H_
