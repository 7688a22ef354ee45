// Longest-edge refinement of an input mesh to an exact triangle count: the
// real Stanford dragon (871,414 triangles) at the size of the report's scene 3
// (asianDragon, 7,219,045 triangles) and of scene 11 (buddha, 1,087,474).
//
// Repeatedly the longest edge of the mesh is split at its midpoint, and every
// triangle that has this edge is split in two (Rivara's longest-edge
// bisection; M.-C. Rivara, "Algorithms for refining triangular grids suitable
// for adaptive and multigrid techniques", IJNME 20, 1984). New vertices lie on
// the input's edges, so the surface is unchanged (no smoothing, no detail
// added) and the mesh stays conforming (no T-junctions) except, at most, for
// one last split that adds a single triangle to reach an odd remainder.
// Splitting the longest edges first evens out triangle sizes, as a finer scan
// of the same object would have them. Triangles of zero area (in the input,
// or made by rounding when a sliver is split) are dropped, as the loader
// (cc/io) drops them, so that the count is also the count loaded.
#ifndef KDTREE_CC_SCENES_REFINE_H_
#define KDTREE_CC_SCENES_REFINE_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct RefineConfig {
  // Triangles wanted; the result has exactly this many non-degenerate
  // triangles when it is at least the input's non-degenerate count (otherwise
  // the input's non-degenerate triangles are returned).
  int64_t target_triangles = 0;
};

Mesh RefineMesh(const RefineConfig& config, const Mesh& input);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_REFINE_H_
