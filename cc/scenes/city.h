// City: blocks of box buildings with setbacks, a ledge at every floor, window
// sills and rooftop boxes, streets with bollards (stand-in for the report's
// scenes 4 city2 and 5 city). Mostly axis-aligned boxes, like real city
// models, so many triangles share a few split planes.
#ifndef KDTREE_CC_SCENES_CITY_H_
#define KDTREE_CC_SCENES_CITY_H_

#include <cstdint>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct CityConfig {
  // Triangles wanted, hit exactly: buildings are added block by block in
  // rings around the centre while they fit, then bollards (12 triangles),
  // road marks (2) and at most one marker triangle fill the rest.
  int64_t target_triangles = 75420;
  uint64_t seed = 1;
  int lots_per_side = 3;       // a block is lots_per_side x lots_per_side lots
  float lot_size = 12.0f;      // metres
  float street_width = 10.0f;  // metres
  float floor_height = 3.0f;   // metres
  int max_floors = 24;         // at the centre; fewer towards the outskirts
  float window_pitch = 3.0f;   // metres between window sills along a facade
};

// y up; ground is the quad y = 0 under all blocks.
Mesh GenerateCity(const CityConfig& config);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_CITY_H_
