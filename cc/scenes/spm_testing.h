// Test-only writer of .spm files (the layout documented in spm.h), to build
// small synthetic meshes with every optional vertex attribute.
#ifndef KDTREE_CC_SCENES_SPM_TESTING_H_
#define KDTREE_CC_SCENES_SPM_TESTING_H_

#include <string>
#include <utility>
#include <vector>

#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct SpmWriteOptions {
  bool skinned = false;
  bool normals = false;
  // Vertex colours: even vertices white (1 byte), odd ones RGB (4 bytes).
  bool colors = false;
  bool tangents = false;
  // Texture 1 and 2 names per material; an empty name 1 means no UVs.
  std::vector<std::pair<std::string, std::string>> materials = {{"", ""}};
  // Bytes appended after the last buffer (a skinned mesh's armature).
  std::string trailer;
};

struct SpmTestBuffer {
  Mesh mesh;
  uint16_t material = 0;
};

// One section per inner vector. The header's bounding box is that of all
// vertices.
std::string EncodeSpm(const SpmWriteOptions& options,
                      const std::vector<std::vector<SpmTestBuffer>>& sections);

// A one-buffer, one-section file of `mesh` with default options.
std::string EncodeSpm(const Mesh& mesh);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_SPM_TESTING_H_
