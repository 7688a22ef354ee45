#include "cc/scenes/assimp_mesh.h"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "assimp/Importer.hpp"
#include "assimp/postprocess.h"
#include "assimp/scene.h"

namespace kdtree {
namespace scenes {
namespace {

bool MeshUsable(const aiMesh* mesh) {
  return mesh != nullptr && (mesh->mNumFaces == 0 || mesh->mFaces != nullptr) &&
         (mesh->mNumVertices == 0 || mesh->mVertices != nullptr);
}

bool FaceUsable(const aiMesh& mesh, const aiFace& face) {
  if (face.mNumIndices > 0 && face.mIndices == nullptr) return false;
  for (unsigned i = 0; i < face.mNumIndices; ++i) {
    if (face.mIndices[i] >= mesh.mNumVertices) return false;
  }
  return true;
}

// One instance of `mesh` under `transform`: its triangles into `out` (when
// not null), its faces into the totals.
void AddInstance(const aiMesh& mesh, const aiMatrix4x4& transform, FlattenTotals& t, Mesh* out) {
  ++t.instances;
  // Output index of each of this instance's vertices (shared as assimp's
  // reader shares them).
  std::vector<int32_t> remap(out != nullptr ? mesh.mNumVertices : 0, -1);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (!FaceUsable(mesh, face)) {
      ++t.dropped;
      continue;
    }
    if (face.mNumIndices == 1) ++t.points;
    if (face.mNumIndices == 2) ++t.lines;
    if (face.mNumIndices != 3) continue;
    ++t.triangles;
    int32_t index[3];
    for (unsigned i = 0; i < 3; ++i) {
      const aiVector3D p = transform * mesh.mVertices[face.mIndices[i]];
      const double c[3] = {p.x, p.y, p.z};
      for (int a = 0; a < 3; ++a) {
        if (c[a] < t.lo[a]) t.lo[a] = c[a];
        if (c[a] > t.hi[a]) t.hi[a] = c[a];
      }
      if (out != nullptr) {
        int32_t& r = remap[face.mIndices[i]];
        if (r < 0) r = out->AddVertex(Vec3(p.x, p.y, p.z));
        index[i] = r;
      }
    }
    if (out != nullptr) out->AddTriangle(index[0], index[1], index[2]);
  }
}

// `skip`: node names left out with their subtrees.
void Walk(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, int depth,
          const std::set<std::string>& skip, FlattenTotals& t, Mesh* out) {
  if (depth > 1000) {  // a cyclic or absurd node graph
    ++t.dropped;
    return;
  }
  if (!skip.empty() && skip.count(node.mName.C_Str()) > 0) {
    ++t.skipped_nodes;
    return;
  }
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (node.mMeshes == nullptr || node.mMeshes[k] >= scene.mNumMeshes ||
        scene.mMeshes == nullptr || !MeshUsable(scene.mMeshes[node.mMeshes[k]])) {
      ++t.dropped;
      continue;
    }
    AddInstance(*scene.mMeshes[node.mMeshes[k]], transform, t, out);
  }
  if (node.mNumChildren > 0 && node.mChildren == nullptr) {
    ++t.dropped;
    return;
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    if (node.mChildren[c] == nullptr) {
      ++t.dropped;
      continue;
    }
    Walk(scene, *node.mChildren[c], transform, depth + 1, skip, t, out);
  }
}

}  // namespace

FlattenTotals::FlattenTotals() {
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -std::numeric_limits<double>::infinity();
  }
}

absl::Status ReadFlattened(const std::string& path, const std::set<std::string>& skip_nodes,
                           FlattenTotals* totals, Mesh* out) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return absl::InvalidArgumentError(
        absl::StrCat("assimp cannot read ", path, ": ", importer.GetErrorString()));
  }
  FlattenTotals& t = *totals;
  Walk(*scene, *scene->mRootNode, aiMatrix4x4(), 0, skip_nodes, t, out);
  t.meshes = scene->mNumMeshes;
  for (unsigned m = 0; scene->mMeshes != nullptr && m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!MeshUsable(mesh)) continue;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      t.triangles_unique += mesh->mFaces[f].mNumIndices == 3 && FaceUsable(*mesh, mesh->mFaces[f]);
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<Mesh> ReadMesh(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::is_regular_file(status)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "mesh ", path, ": ", ec ? ec.message() : std::string("not a regular file")));
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kSceneInputBudget) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "mesh ", path, ": ", ec ? ec.message() : absl::StrCat(size, " bytes, over the budget of ",
                                                             kSceneInputBudget)));
  }
  Mesh mesh;
  FlattenTotals totals;
  if (absl::Status s = ReadFlattened(path, {}, &totals, &mesh); !s.ok()) return s;
  if (mesh.faces.empty()) return absl::InvalidArgumentError(absl::StrCat("mesh ", path, ": no triangles"));
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
