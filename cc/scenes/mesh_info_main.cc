// Counts what a renderer gets from a mesh file through assimp: loads it with
// aiProcess_Triangulate, walks the node hierarchy (a mesh referenced by k
// nodes counts k times, as a flattened scene has it), and prints one JSON line:
//   {"triangles": flattened triangles, "triangles_unique": sum over meshes,
//    "lines": .., "points": .., "meshes": .., "instances": ..,
//    "bounds": [[lo], [hi]]}   (bounds of the flattened triangles)
// Used by data/fetch.py to check each scene it brings in (run it as a child
// process: some readers crash on some files).
//
//   bazel run //cc/scenes:mesh_info -- /abs/path/scene.blend
#include <cstdio>
#include <limits>

#include "assimp/Importer.hpp"
#include "assimp/postprocess.h"
#include "assimp/scene.h"

namespace {

struct Totals {
  unsigned long long triangles = 0, lines = 0, points = 0, instances = 0;
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
};

void Walk(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, Totals& t) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    ++t.instances;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 1) ++t.points;
      if (face.mNumIndices == 2) ++t.lines;
      if (face.mNumIndices != 3) continue;
      ++t.triangles;
      for (unsigned i = 0; i < 3; ++i) {
        const aiVector3D p = transform * mesh.mVertices[face.mIndices[i]];
        const double c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
          if (c[a] < t.lo[a]) t.lo[a] = c[a];
          if (c[a] > t.hi[a]) t.hi[a] = c[a];
        }
      }
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) Walk(scene, *node.mChildren[c], transform, t);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mesh_info FILE\n");
    return 2;
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(argv[1], aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::fprintf(stderr, "mesh_info: assimp cannot read %s: %s\n", argv[1],
                 importer.GetErrorString());
    return 1;
  }
  Totals t;
  Walk(*scene, *scene->mRootNode, aiMatrix4x4(), t);
  unsigned long long unique = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) unique += mesh.mFaces[f].mNumIndices == 3;
  }
  std::printf(
      "{\"triangles\": %llu, \"triangles_unique\": %llu, \"lines\": %llu, \"points\": %llu, "
      "\"meshes\": %u, \"instances\": %llu, \"bounds\": [[%.9g, %.9g, %.9g], [%.9g, %.9g, "
      "%.9g]]}\n",
      t.triangles, unique, t.lines, t.points, scene->mNumMeshes, t.instances, t.lo[0], t.lo[1],
      t.lo[2], t.hi[0], t.hi[1], t.hi[2]);
  return t.triangles > 0 ? 0 : 1;
}
