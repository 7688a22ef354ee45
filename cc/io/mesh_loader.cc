#include "cc/io/mesh_loader.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <chrono>
#include <cmath>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "cc/geometry/exact_area.h"
#include "cc/io/mesh_input.h"
#include "cc/io/mesh_syntax.h"

namespace kdtree {
namespace {

// The only post-processing: polygons -> triangles, node transforms applied.
constexpr unsigned int kAssimpFlags = aiProcess_Triangulate | aiProcess_PreTransformVertices;

inline bool SaneCoordinate(float x) { return std::fabs(x) <= kMaxAbsCoordinate; }  // NaN fails

inline Vec3 ToVec3(const aiVector3D& p) {
  return Vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
}

// Checks what post-processing relies on: meshes exist, face and node indices
// are in range. Reports the first problem.
absl::Status ValidateScene(const std::string& path, const aiScene& scene) {
  auto malformed = [&path](const std::string& why) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     absl::StrCat("malformed or truncated mesh: ", why));
  };
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr) return malformed("missing mesh array");
  for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr) return malformed(absl::StrCat("mesh ", m, " is missing"));
    if (mesh->mNumFaces > 0 && mesh->mFaces == nullptr) {
      return malformed(absl::StrCat("mesh ", m, " has no face array"));
    }
    if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr) {
      return malformed(absl::StrCat("mesh ", m, " has no vertex array"));
    }
    for (unsigned int f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices > 0 && face.mIndices == nullptr) {
        return malformed(absl::StrCat("mesh ", m, " face ", f, " has no index array"));
      }
      for (unsigned int k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          return malformed(absl::StrCat("mesh ", m, " face ", f, " uses vertex ",
                                        face.mIndices[k], " of ", mesh->mNumVertices));
        }
      }
    }
  }
  std::vector<const aiNode*> stack;
  if (scene.mRootNode != nullptr) stack.push_back(scene.mRootNode);
  size_t visited = 0;
  while (!stack.empty()) {
    if (++visited > (size_t{1} << 24)) return malformed("node graph too large or cyclic");
    const aiNode* node = stack.back();
    stack.pop_back();
    for (unsigned int i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes == nullptr || node->mMeshes[i] >= scene.mNumMeshes) {
        return malformed("a node refers to a mesh that does not exist");
      }
    }
    for (unsigned int i = 0; i < node->mNumChildren; ++i) {
      if (node->mChildren == nullptr || node->mChildren[i] == nullptr) {
        return malformed("a node has a missing child");
      }
      stack.push_back(node->mChildren[i]);
    }
  }
  return absl::OkStatus();
}

// Appends the scene's triangles to `soup`, filtering and counting.
absl::Status CollectTriangles(const std::string& path, const aiScene& scene,
                              const LoadOptions& options, TriangleSoup* soup,
                              LoadReport* report) {
  size_t faces = 0;
  for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
    if (scene.mMeshes[m] != nullptr) faces += scene.mMeshes[m]->mNumFaces;
  }
  soup->v.reserve(3 * faces);
  for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr) continue;
    if (mesh->mFaces == nullptr || mesh->mVertices == nullptr) {
      report->skipped_faces += mesh->mNumFaces;
      continue;
    }
    for (unsigned int f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3 || face.mIndices == nullptr) {
        ++report->skipped_faces;
        continue;
      }
      for (unsigned int k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          return FileError(absl::StatusCode::kInvalidArgument, path,
                           absl::StrCat("malformed mesh: mesh ", m, " face ", f,
                                        " has vertex index ", face.mIndices[k], " but only ",
                                        mesh->mNumVertices, " vertices"));
        }
      }
      // Triangulate leaves only triangles; a fan covers any polygon it missed.
      const Vec3 a = ToVec3(mesh->mVertices[face.mIndices[0]]);
      for (unsigned int k = 1; k + 1 < face.mNumIndices; ++k) {
        const Vec3 b = ToVec3(mesh->mVertices[face.mIndices[k]]);
        const Vec3 c = ToVec3(mesh->mVertices[face.mIndices[k + 1]]);
        if (!IsSaneTriangle(a, b, c)) {
          ++report->dropped_nonfinite;
        } else if (options.drop_degenerate && IsDegenerateTriangle(a, b, c)) {
          ++report->dropped_degenerate;
        } else {
          soup->Add(a, b, c);
        }
      }
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<TriangleSoup> LoadMeshImpl(const std::string& path, const LoadOptions& options,
                                          LoadReport* report) {
  if (path.empty()) {
    return absl::InvalidArgumentError("LoadMesh: empty mesh path");
  }
  absl::StatusOr<MeshInput> input = ReadMeshInput(path, options.max_input_bytes);
  if (!input.ok()) return input.status();
  MeshInput& in = *input;

  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    // OBJ, OFF and PLY are checked first (mesh_syntax.h): assimp accepts or
    // aborts on some malformed files of these formats.
    if (NeedsSyntaxCheck(in.format)) {
      if (absl::Status s = CheckMeshSyntax(in.bytes, in.format, path); !s.ok()) return s;
    }
    // The bytes are freed as soon as they are not needed: after the syntax
    // check when assimp reads the file itself, after the import otherwise.
    if (in.in_memory) {
      scene = importer.ReadFileFromMemory(in.bytes.data(), in.bytes.size(), 0, in.format.c_str());
      std::string().swap(in.bytes);
    } else {
      std::string().swap(in.bytes);
      scene = importer.ReadFile(path, 0);
    }
    // Post-processing trusts the importer's indices (assimp 5.2's Triangulate
    // segfaults on a truncated binary PLY), so check them first.
    if (scene != nullptr) {
      if (absl::Status s = ValidateScene(path, *scene); !s.ok()) return s;
      scene = importer.ApplyPostProcessing(kAssimpFlags);
    }
  } catch (const std::bad_alloc&) {
    return FileError(absl::StatusCode::kResourceExhausted, path, "out of memory while importing");
  } catch (const std::exception& e) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     absl::StrCat("assimp import failed: ", e.what()));
  } catch (...) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     "assimp import failed with an unknown exception");
  }
  if (scene == nullptr) {
    const char* err = importer.GetErrorString();
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     absl::StrCat("assimp cannot import it: ",
                                  (err != nullptr && *err != '\0') ? err : "unknown error"));
  }

  TriangleSoup soup;
  try {
    if (absl::Status s = CollectTriangles(path, *scene, options, &soup, report); !s.ok()) {
      return s;
    }
  } catch (const std::bad_alloc&) {
    return FileError(absl::StatusCode::kResourceExhausted, path,
                     "out of memory while collecting triangles");
  }
  if (soup.empty()) {
    return FileError(
        absl::StatusCode::kInvalidArgument, path,
        absl::StrCat("no triangles in the scene (", scene->mNumMeshes, " meshes, ",
                     report->skipped_faces, " point/line faces skipped, ",
                     report->dropped_degenerate, " degenerate and ", report->dropped_nonfinite,
                     " non-finite triangles dropped)"));
  }
  report->triangles = soup.size();
  return soup;
}

}  // namespace

bool IsSaneTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return SaneCoordinate(a.x) && SaneCoordinate(a.y) && SaneCoordinate(a.z) &&
         SaneCoordinate(b.x) && SaneCoordinate(b.y) && SaneCoordinate(b.z) &&
         SaneCoordinate(c.x) && SaneCoordinate(c.y) && SaneCoordinate(c.z);
}

bool IsDegenerateTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return HasZeroArea(a, b, c);  // exact (cc/geometry/exact_area.h)
}

absl::StatusOr<TriangleSoup> LoadMesh(const std::string& path, LoadReport* report,
                                      const LoadOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  LoadReport local;
  LoadReport* r = report != nullptr ? report : &local;
  *r = LoadReport();
  absl::StatusOr<TriangleSoup> soup = LoadMeshImpl(path, options, r);
  r->load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return soup;
}

}  // namespace kdtree
