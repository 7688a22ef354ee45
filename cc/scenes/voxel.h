// Voxel world: a Minecraft-like landscape (stand-in for the report's scenes 13
// lost.empire, 242,870 triangles, and 15 rungholt, 6,704,264 triangles).
//
// Unit blocks on the integer lattice: a noise heightfield, caves carved by 3D
// noise, hollow buildings with windows and doors, and block trees. Only block
// faces between a solid block and an empty cell are emitted, 2 triangles per
// face, so every vertex has integer coordinates and every triangle lies exactly
// in an axis-aligned integer plane: the hardest case for kd-tree split planes
// (many triangles lie in the candidate planes themselves).
#ifndef KDTREE_CC_SCENES_VOXEL_H_
#define KDTREE_CC_SCENES_VOXEL_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct VoxelConfig {
  // Triangles wanted; the world's width and depth (in blocks, aspect between
  // 3:4 and 4:3) are searched for the count closest to it. 0: use width/depth.
  int64_t target_triangles = 242870;
  int width = 128;  // x extent in blocks, when target_triangles == 0
  int depth = 128;  // z extent in blocks, when target_triangles == 0
  uint64_t seed = 1;
  // Fraction of 24x24 plots holding a building.
  float building_density = 0.35f;
  // Fraction of free 8x8 plots holding a tree.
  float tree_density = 0.3f;
  // Threshold of the cave noise in [0, 1]: higher means fewer caves (1: none).
  float cave_threshold = 0.74f;
};

// The world spans [0, width] x [0, 64] x [0, depth], y up; the world is closed
// (its sides and bottom are emitted too).
Mesh GenerateVoxel(const VoxelConfig& config);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_VOXEL_H_
