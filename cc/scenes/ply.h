// Minimal mesh file I/O for the scene generators.
//
// Writer: binary little-endian PLY, the only output format of the generators:
//   element vertex N  (property float x, y, z)
//   element face M    (property list uchar int vertex_indices)
// The bytes depend only on the mesh, so equal meshes give equal files.
//
// Reader: enough to take an input mesh for instancing (the teapots generator):
// PLY (ascii or binary_little_endian; x/y/z of any scalar type; polygons of
// `vertex_indices`/`vertex_index`; other elements and properties skipped) and
// OBJ (`v` and `f` lines only). Polygons are split into a fan of triangles.
#ifndef KDTREE_CC_SCENES_PLY_H_
#define KDTREE_CC_SCENES_PLY_H_

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

// The complete binary PLY file for `mesh`.
std::string EncodePly(const Mesh& mesh);
absl::Status WritePly(const std::string& path, const Mesh& mesh);

absl::StatusOr<Mesh> ParsePly(absl::string_view bytes);
absl::StatusOr<Mesh> ParseObj(absl::string_view text);
// Dispatches on the extension (.ply or .obj, case-insensitive).
absl::StatusOr<Mesh> ReadMesh(const std::string& path);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_PLY_H_
