// Forest: trees on a noise terrain (stand-in for the report's scene 7,
// fforest). A tree is a bent, tapered trunk cylinder and a few clusters of
// small free-floating leaf triangles in random orientations; grass blades
// (one triangle each) fill the triangle budget exactly.
#ifndef KDTREE_CC_SCENES_FOREST_H_
#define KDTREE_CC_SCENES_FOREST_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct ForestConfig {
  // Triangles wanted, hit exactly (terrain + trees + grass blades).
  int64_t target_triangles = 174117;
  uint64_t seed = 1;
  float tree_spacing = 6.0f;    // metres between trees (jittered grid)
  int trunk_sides = 6;          // cross-section of a trunk
  int trunk_segments = 5;       // rings along a trunk
  int min_leaves = 300;         // leaf triangles per tree, drawn from
  int max_leaves = 900;         // [min_leaves, max_leaves)
  float leaf_size = 0.35f;      // metres, edge of a leaf triangle
  float terrain_relief = 8.0f;  // metres between the lowest and highest ground
};

// y up; the terrain is a regular grid around the origin.
Mesh GenerateForest(const ForestConfig& config);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_FOREST_H_
