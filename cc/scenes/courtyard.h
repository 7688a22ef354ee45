// Courtyard: real packaged trees, plants and garden furniture instanced into
// an arcaded courtyard, stand-in for the report's scene 16 (san-miguel,
// 9,980,699 triangles: G. M. Leal LLaguno's San Miguel hacienda courtyard,
// dense foliage, tables and chairs under arcades; M. McGuire, Computer
// Graphics Archive, 2017).
//
// Parts (assembly.h), by role:
//   tree     required; one per planted cell, in turn
//   plant    potted plants: around each tree, in the arcade, and the filler
//   table, chair   a table with four chairs in each café cell
//   column   the arcade's columns (else box pillars)
//   fountain the centre cell
// The courtyard is a square of 6 m cells (tiled floor; a third of the cells
// are cafés, the rest planted) inside a two-storey arcade (columns every 3 m,
// slabs, back walls). Its side is chosen so that the cells hold about the
// target; cells are filled in a seeded order until the next would pass it,
// then potted plants close most of the gap and a fan closes it exactly.
// Output is y-up, metres. Deterministic: same parts, seed and size, same bytes.
#ifndef KDTREE_CC_SCENES_COURTYARD_H_
#define KDTREE_CC_SCENES_COURTYARD_H_

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/scenes/assembly.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct CourtyardConfig {
  int64_t target_triangles = 9980699;
  uint64_t seed = 16;
  float cell = 6;           // metres
  float cafe_share = 0.33f;  // share of cells that are cafés
  float arcade_depth = 4;   // metres
  float storey = 4;         // metres
};

// Fails without a "tree" part or when the frame alone passes the target.
absl::StatusOr<Mesh> GenerateCourtyard(const CourtyardConfig& config, const std::vector<Part>& parts);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_COURTYARD_H_
