// Midpoint subdivision of an input mesh (each triangle into 4 by its edge
// midpoints, shared edges split once): a real scan at the triangle counts of
// the report's largest scanned models (scene 3 asianDragon, 7,219,045
// triangles) from the 871,414-triangle Stanford dragon. Adds triangles, not
// detail: the surface is unchanged, its triangles get 4x smaller per level.
#ifndef KDTREE_CC_SCENES_SUBDIVIDE_H_
#define KDTREE_CC_SCENES_SUBDIVIDE_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct SubdivideConfig {
  // Triangles wanted: the number of levels is the one whose count
  // (input * 4^levels) is closest to it in ratio; at least 0.
  int64_t target_triangles = 0;
  // Used when target_triangles <= 0.
  int levels = 1;
};

// Number of levels SubdivideMesh will apply to a mesh of `input` triangles.
int SubdivisionLevels(const SubdivideConfig& config, int64_t input);

Mesh SubdivideMesh(const SubdivideConfig& config, const Mesh& input);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_SUBDIVIDE_H_
