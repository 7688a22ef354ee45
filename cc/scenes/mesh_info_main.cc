// Counts what a renderer gets from a mesh file through assimp: loads it with
// aiProcess_Triangulate, walks the node hierarchy (a mesh referenced by k
// nodes counts k times, as a flattened scene has it), and prints one JSON line:
//   {"triangles": flattened triangles, "triangles_unique": sum over meshes,
//    "lines": .., "points": .., "meshes": .., "instances": ..,
//    "dropped": faces/meshes skipped because the reader left them malformed,
//    "skipped_nodes": nodes left out by --skip_nodes (with their subtrees),
//    "bounds": [[lo], [hi]]}   (bounds of the flattened triangles)
// --skip_nodes=A,B leaves out every node named A or B and its subtree: helper
// geometry a scene file carries but never draws (FlightGear's Cessna has two
// 200 m light cones around an 8 m aircraft).
// With --ply_out=PATH it also writes the flattened triangles as binary PLY
// (cc/scenes/ply.h), the form in which fetch.py keeps scenes whose reader is
// fragile (Quake 3 maps in a .pk3; the TORCS .acc variant of AC3D): the
// loaders then read a plain file.
//
// Malformed reader output is skipped and counted, never dereferenced: assimp
// 5.2's Q3BSP reader leaves node mesh indices past the mesh array on the
// Nexuiz maps. Used by data/fetch.py as a child process (some readers still
// crash on some files).
//
//   bazel run //cc/scenes:mesh_info -- /abs/path/scene.blend [--ply_out=/abs/out.ply]
#include <cstdint>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "assimp/Importer.hpp"
#include "assimp/postprocess.h"
#include "assimp/scene.h"
#include "cc/base/json_line.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, ply_out, "", "also write the flattened triangles to this binary PLY");
ABSL_FLAG(std::vector<std::string>, skip_nodes, {},
          "comma-separated node names left out with their subtrees (helper geometry)");

namespace {

using kdtree::Vec3;
using kdtree::scenes::Mesh;

struct Totals {
  unsigned long long triangles = 0, lines = 0, points = 0, instances = 0, dropped = 0;
  unsigned long long skipped_nodes = 0;
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
};

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

// `skip`: node names left out with their subtrees (--skip_nodes).
void Walk(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, int depth,
          const std::set<std::string>& skip, Totals& t, Mesh* out) {
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
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    ++t.instances;
    // Output index of each of this instance's vertices (shared as in the file).
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

int main(int argc, char** argv) {
  const std::vector<char*> args = absl::ParseCommandLine(argc, argv);
  if (args.size() != 2) {
    std::fprintf(stderr, "usage: mesh_info FILE [--ply_out=OUT.ply] [--skip_nodes=A,B]\n");
    return 2;
  }
  const char* path = args[1];
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::fprintf(stderr, "mesh_info: assimp cannot read %s: %s\n", path,
                 importer.GetErrorString());
    return 1;
  }
  const std::string ply_out = absl::GetFlag(FLAGS_ply_out);
  Mesh flattened;
  Totals t;
  std::set<std::string> skip;
  for (const std::string& name : absl::GetFlag(FLAGS_skip_nodes)) {
    if (!name.empty()) skip.insert(name);
  }
  Walk(*scene, *scene->mRootNode, aiMatrix4x4(), 0, skip, t,
       ply_out.empty() ? nullptr : &flattened);
  unsigned long long unique = 0;
  for (unsigned m = 0; scene->mMeshes != nullptr && m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!MeshUsable(mesh)) continue;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      unique += mesh->mFaces[f].mNumIndices == 3 && FaceUsable(*mesh, mesh->mFaces[f]);
    }
  }
  if (!ply_out.empty() && t.triangles > 0) {
    const absl::Status s = kdtree::scenes::WritePly(ply_out, flattened);
    if (!s.ok()) {
      std::fprintf(stderr, "mesh_info: %s\n", s.ToString().c_str());
      return 1;
    }
  }
  const nlohmann::ordered_json line = {
      {"triangles", t.triangles},
      {"triangles_unique", unique},
      {"lines", t.lines},
      {"points", t.points},
      {"meshes", scene->mNumMeshes},
      {"instances", t.instances},
      {"dropped", t.dropped},
      {"skipped_nodes", t.skipped_nodes},
      {"bounds", {{t.lo[0], t.lo[1], t.lo[2]}, {t.hi[0], t.hi[1], t.hi[2]}}}};
  std::printf("%s\n", kdtree::JsonLine(line).c_str());
  return t.triangles > 0 ? 0 : 1;
}
