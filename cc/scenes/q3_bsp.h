// Quake 3 map reader (IBSP version 46, as written by q3map/q3map2; Nexuiz
// and OpenArena maps): the drawn surfaces of a .bsp as one triangle mesh.
//
// Written by us from the format (the map compiler's lumps: textures 1,
// vertices 10, mesh vertices 11, faces 13; K. Proudfoot, "Unofficial Quake 3
// Map Specs", 2000) because assimp 5.2's Q3BSP reader mis-builds these maps:
// on Nexuiz's ons-reborn it returns 124,981 triangles of which all but two
// are degenerate, and node mesh indices past its mesh array.
//
// Faces of type 1 (polygon) and 3 (mesh) are the triangles their mesh-vertex
// lists give; type 2 (Bezier patch, 3x3 biquadratic control grids) is
// tessellated at `patch_subdivisions` steps per patch side; type 4
// (billboard flare) has no geometry. Surfaces the game never draws as
// geometry are skipped: sky (surface flag 0x4) and nodraw (0x80). Output is
// the map's frame: z up, units as in the game.
#ifndef KDTREE_CC_SCENES_Q3_BSP_H_
#define KDTREE_CC_SCENES_Q3_BSP_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct Q3BspConfig {
  // Quads per side of each 3x3 Bezier patch (2 * n * n triangles per patch).
  int patch_subdivisions = 8;
  // Skip surfaces whose texture has the sky flag (the map's sky box).
  bool skip_sky = true;
  // Skip surfaces whose texture has the nodraw flag.
  bool skip_nodraw = true;
};

struct Q3BspStats {
  int64_t faces = 0;            // faces in the map
  int64_t polygon_faces = 0;    // type 1 and 3 faces kept
  int64_t patch_faces = 0;      // type 2 faces kept
  int64_t skipped_faces = 0;    // sky, nodraw, billboards, unknown types
};

// Parses a whole .bsp file. Fails on anything but IBSP version 46 and on
// indices outside their lumps.
absl::StatusOr<Mesh> ParseQ3Bsp(absl::string_view bytes, const Q3BspConfig& config,
                                Q3BspStats* stats = nullptr);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_Q3_BSP_H_
