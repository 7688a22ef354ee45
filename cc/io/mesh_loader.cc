#include "cc/io/mesh_loader.h"

#include <sys/stat.h>
#include <zlib.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "cc/geometry/exact_area.h"
#include "cc/io/mesh_syntax.h"

namespace kdtree {
namespace {

// The only post-processing: polygons -> triangles, node transforms applied.
constexpr unsigned int kAssimpFlags = aiProcess_Triangulate | aiProcess_PreTransformVertices;

absl::Status FileError(absl::StatusCode code, const std::string& path, const std::string& why) {
  return absl::Status(code, absl::StrCat(path, ": ", why));
}

// Missing, directory, unreadable and empty files get their own clear message.
absl::Status CheckReadableFile(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      return FileError(absl::StatusCode::kNotFound, path, "file not found");
    }
    return FileError(absl::StatusCode::kUnavailable, path,
                     absl::StrCat("cannot stat file: ", std::strerror(err)));
  }
  if (S_ISDIR(st.st_mode)) {
    return FileError(absl::StatusCode::kInvalidArgument, path, "is a directory, not a mesh file");
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    return FileError(err == EACCES ? absl::StatusCode::kPermissionDenied
                                   : absl::StatusCode::kUnavailable,
                     path, absl::StrCat("cannot open file: ", std::strerror(err)));
  }
  std::fclose(f);
  if (S_ISREG(st.st_mode) && st.st_size == 0) {
    return FileError(absl::StatusCode::kInvalidArgument, path, "file is empty");
  }
  return absl::OkStatus();
}

// Decompresses a whole gzip file into `out`.
absl::Status ReadGzip(const std::string& path, std::string* out) {
  gzFile gz = gzopen(path.c_str(), "rb");
  if (gz == nullptr) {
    return FileError(absl::StatusCode::kUnavailable, path, "cannot open gzip file");
  }
  gzbuffer(gz, 1 << 20);
  if (gzdirect(gz)) {
    gzclose_r(gz);
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     "name ends in .gz but the file is not gzip-compressed");
  }
  constexpr size_t kChunk = size_t{1} << 22;
  out->clear();
  try {
    for (;;) {
      const size_t old = out->size();
      out->resize(old + kChunk);
      const int n = gzread(gz, &(*out)[old], static_cast<unsigned>(kChunk));
      if (n < 0) {
        out->resize(old);
        break;
      }
      out->resize(old + static_cast<size_t>(n));
      if (n == 0) break;
    }
  } catch (const std::bad_alloc&) {
    gzclose_r(gz);
    out->clear();
    return FileError(absl::StatusCode::kResourceExhausted, path,
                     "out of memory while decompressing gzip data");
  }
  int errnum = Z_OK;
  const char* msg = gzerror(gz, &errnum);
  const std::string why = (msg != nullptr && *msg != '\0') ? msg : "unknown error";
  gzclose_r(gz);
  if (errnum != Z_OK) {
    out->clear();
    return FileError(absl::StatusCode::kDataLoss, path,
                     absl::StrCat("corrupt or truncated gzip data (zlib: ", why, ")"));
  }
  if (out->empty()) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     "file is empty after gzip decompression");
  }
  return absl::OkStatus();
}

// Reads a whole (uncompressed) file into `out`.
absl::Status ReadWholeFile(const std::string& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (!in.good() && !in.eof()) {
    return FileError(absl::StatusCode::kUnavailable, path, "cannot read file");
  }
  *out = std::move(ss).str();
  return absl::OkStatus();
}

// Lower-case extension of the file name without the dot ("" when none).
std::string Extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t start = slash == std::string::npos ? 0 : slash + 1;
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || dot < start || dot + 1 == path.size()) return "";
  return absl::AsciiStrToLower(path.substr(dot + 1));
}

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
  if (absl::Status s = CheckReadableFile(path); !s.ok()) return s;

  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    if (absl::EndsWithIgnoreCase(path, ".gz")) {
      std::string data;
      if (absl::Status s = ReadGzip(path, &data); !s.ok()) return s;
      const std::string hint = Extension(path.substr(0, path.size() - 3));
      if (absl::Status s = CheckMeshSyntax(data, hint, path); !s.ok()) return s;
      scene = importer.ReadFileFromMemory(data.data(), data.size(), 0, hint.c_str());
    } else {
      // OBJ, OFF and PLY are checked first (mesh_syntax.h): assimp accepts or
      // aborts on some malformed files of these formats.
      const std::string ext = Extension(path);
      if (ext == "obj" || ext == "off" || ext == "ply") {
        std::string data;
        if (absl::Status s = ReadWholeFile(path, &data); !s.ok()) return s;
        if (absl::Status s = CheckMeshSyntax(data, ext, path); !s.ok()) return s;
      }
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
