// Power plant: real packaged machinery instanced into halls with pipe racks,
// stand-in for the report's scene 14 (powerplant, 12,759,246 triangles: a
// CAD model of a coal power plant, dense machinery and pipes inside a large,
// mostly empty site). M. McGuire, Computer Graphics Archive, 2017.
//
// Parts (assembly.h), by role:
//   machine      required; two per bay on plinths (the glTF 2-cylinder engine)
//   tank, vessel, transformer   optional; one per bay, in turn
//   tower, chimney, building    optional; a row of each behind the halls
// Bays (24 m x 16 m: floor slab, machines, risers, an 8-pipe rack on posts)
// fill a square grid, row by row, until the next bay would pass the target;
// long header pipes then close most of the gap, and a fan closes it exactly.
// Output is y-up, metres. Deterministic: same parts, seed and size, same bytes.
#ifndef KDTREE_CC_SCENES_PLANT_H_
#define KDTREE_CC_SCENES_PLANT_H_

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/scenes/assembly.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct PlantConfig {
  int64_t target_triangles = 12759246;
  uint64_t seed = 14;
  float bay_x = 24, bay_z = 16;  // metres
  int machines_per_bay = 2;
  int rack_pipes = 8;        // pipes per bay's rack
  int pipe_sides = 16;       // tube resolution
  float pipe_segment = 1.0f;  // metres per tube segment
};

// Fails without a "machine" part or when the site alone passes the target.
absl::StatusOr<Mesh> GeneratePlant(const PlantConfig& config, const std::vector<Part>& parts);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_PLANT_H_
