// Mesh files as the scene tools read them: through assimp, the project's one
// reader of outside mesh formats (cc/io/mesh_loader.h loads the same files
// for the renderer). The scene is read with aiProcess_Triangulate and its node
// hierarchy flattened: a mesh referenced by k nodes counts k times, with the
// nodes' transforms applied, as a flattened scene has it. Within one instance
// vertices are shared as assimp's reader shares them, numbered in the order
// faces first use them: PLY keeps the file's indices, while assimp's OBJ
// reader gives every face corner a vertex of its own (so subdivide and refine,
// which split shared edges, want PLY inputs; fetch.py gives them PLY).
//
// Malformed reader output is skipped and counted, never dereferenced: assimp
// 5.2's Q3BSP reader leaves node mesh indices past the mesh array on the
// Nexuiz maps. The triangulation runs inside assimp's ReadFile, and assimp
// 5.2's post-processing can crash on face indices past the vertex array (a
// truncated binary PLY; cc/io/mesh_loader.h checks them first): the scene
// tools read files data/fetch.py has already read with mesh_info, in a child
// process.
#ifndef KDTREE_CC_SCENES_ASSIMP_MESH_H_
#define KDTREE_CC_SCENES_ASSIMP_MESH_H_

#include <set>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

// What the flattening found (mesh_info prints it).
struct FlattenTotals {
  unsigned long long triangles = 0;         // flattened triangles
  unsigned long long triangles_unique = 0;  // summed over meshes, each once
  unsigned long long lines = 0, points = 0;
  unsigned long long meshes = 0, instances = 0;
  // Faces, meshes or nodes skipped because the reader left them malformed.
  unsigned long long dropped = 0;
  unsigned long long skipped_nodes = 0;  // left out by `skip_nodes`
  double lo[3], hi[3];                   // bounds of the flattened triangles
  FlattenTotals();
};

// Reads `path` with assimp and flattens it into `out` (when not null).
// `skip_nodes`: node names left out with their subtrees (helper geometry a
// scene file carries but never draws). Error: assimp cannot read the file.
absl::Status ReadFlattened(const std::string& path, const std::set<std::string>& skip_nodes,
                           FlattenTotals* totals, Mesh* out);

// The generators' input meshes: a regular file of at most kSceneInputBudget
// bytes, flattened by ReadFlattened, with at least one triangle. Errors name
// the file and the reason.
absl::StatusOr<Mesh> ReadMesh(const std::string& path);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_ASSIMP_MESH_H_
