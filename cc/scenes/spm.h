// Reader of SuperTuxKart's .spm meshes ("SP mesh", version 1): positions and
// triangles only.
//
// The layout below was worked out from the files of Debian's
// supertuxkart-data 1.4 (all 1,222 parse, each consumed to its last byte or,
// when skinned, to its armature; every file's vertices span exactly the
// bounding box of its header; every index is in range). Little-endian:
//
//   "SP"                         magic
//   uint8  version << 3 | type   version 1; type 1 skinned, 2 static
//   uint8  flags                 bit 0 normals, bit 1 colours, bit 2 tangents
//   float  bounds[6]             min x y z, max x y z
//   uint16 M materials, each:    uint8 n, n bytes texture 1 name;
//                                uint8 n, n bytes texture 2 name
//   uint16 S sections, each:     uint16 B buffers, each:
//     uint32 V vertices (<= 65535), uint32 I indices (a multiple of 3),
//     uint16 material (< M), then V vertices of
//       float32 position[3]                                     always
//       4 bytes packed normal                                   normals flag
//       1 byte; 3 more (RGB) unless that byte is 128 (white)    colours flag
//       4 bytes UV (2 x float16)               material has texture 1
//         4 bytes packed tangent               ... and the tangents flag
//         4 bytes second UV                    ... and material has texture 2
//       8 bytes joint indices + 8 bytes weights                 skinned
//     then I indices: uint8 when V < 256, else uint16.
//   Skinned files end with armatures and animation frames: not read (the
//   positions are the bind pose, as the game shows an unanimated mesh).
//
// Every read is bounds-checked: truncated or malformed input gives an error
// naming the file and the reason, never a crash.
#ifndef KDTREE_CC_SCENES_SPM_H_
#define KDTREE_CC_SCENES_SPM_H_

#include <cstddef>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cc/geometry/aabb.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

// What the header and the sections said, besides the mesh.
struct SpmInfo {
  bool skinned = false;
  bool normals = false;
  bool colors = false;
  bool tangents = false;
  int materials = 0;
  int sections = 0;
  int buffers = 0;
  AABB header_bounds;
  // Bytes after the last index buffer (the armature of a skinned mesh).
  size_t trailing_bytes = 0;
};

struct SpmOptions {
  // A static mesh must end with its last index buffer; true accepts trailing
  // bytes anyway (skinned meshes always may have them).
  bool allow_trailing_bytes = false;
  // Every vertex must lie in the header's bounding box, widened by this
  // fraction of its largest extent (the game's exporter writes it exactly).
  // Negative: not checked.
  float bounds_tolerance = 1e-3f;
};

// Parses the bytes of one .spm file; `name` (a path) only labels errors.
// Buffers are concatenated into one indexed mesh.
absl::StatusOr<Mesh> ParseSpm(absl::string_view bytes, absl::string_view name,
                              const SpmOptions& options = {}, SpmInfo* info = nullptr);

absl::StatusOr<Mesh> ReadSpm(const std::string& path, const SpmOptions& options = {},
                             SpmInfo* info = nullptr);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_SPM_H_
