// The scene tools' writer: binary little-endian PLY, the only output format of
// the generators and of mesh_info --ply_out:
//   element vertex N  (property float x, y, z)
//   element face M    (property list uchar int vertex_indices)
// The bytes depend only on the mesh, so equal meshes give equal files. Input
// meshes are read through assimp (assimp_mesh.h), as every other mesh file.
#ifndef KDTREE_CC_SCENES_PLY_H_
#define KDTREE_CC_SCENES_PLY_H_

#include <string>

#include "absl/status/status.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

// The complete binary PLY file for `mesh`.
std::string EncodePly(const Mesh& mesh);
absl::Status WritePly(const std::string& path, const Mesh& mesh);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_PLY_H_
