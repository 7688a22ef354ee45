// Loads a mesh file (anything assimp reads, optionally gzip-compressed) into a
// triangle soup the kd-tree can be built on.
//
// Import: assimp with exactly aiProcess_Triangulate | aiProcess_PreTransformVertices
// (node transforms applied; polygons split by assimp), applied with
// Importer::ApplyPostProcessing after the raw scene's indices are checked
// (assimp 5.2's post-processing crashes on out-of-range indices, e.g. from a
// truncated binary PLY); assimp documents this as equivalent to passing the
// flags to ReadFile. Faces keep assimp's
// order within each mesh and meshes keep the order of the post-processed scene.
// Note that PreTransformVertices itself groups meshes by material (then by
// vertex format, then by node-graph traversal), so for multi-material files
// "scene order" is material order.
//
// OBJ, OFF and PLY files (also gzipped) are first checked by CheckMeshSyntax
// (mesh_syntax.h), whose errors name file, line (or byte) and reason.
//
// Filtering (the kd-tree never sees NaN): faces with fewer than 3 indices
// (points, lines) are skipped; triangles with a NaN/Inf coordinate or one with
// |c| > 1e30 are always dropped; exactly degenerate triangles (collinear or
// repeated vertices, decided by an exact test) are dropped unless
// LoadOptions::drop_degenerate is false. Everything skipped is counted in
// LoadReport.
#ifndef KDTREE_CC_IO_MESH_LOADER_H_
#define KDTREE_CC_IO_MESH_LOADER_H_

#include <cstddef>
#include <string>

#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"
#include "cc/io/mesh_input.h"

namespace kdtree {

struct LoadOptions {
  // Drop triangles of exactly zero area (collinear or coincident vertices).
  bool drop_degenerate = true;
  // Largest file, or inflated .gz, accepted (mesh_input.h): a larger input is
  // refused before it is read or inflated past this.
  size_t max_input_bytes = kMeshInputBudget;
};

struct LoadReport {
  size_t triangles = 0;           // triangles in the returned soup
  size_t skipped_faces = 0;       // faces with fewer than 3 indices
  size_t dropped_degenerate = 0;  // zero-area triangles dropped
  size_t dropped_nonfinite = 0;   // NaN/Inf/|c| > 1e30 triangles dropped
  double load_seconds = 0;        // wall time of the whole load
  bool from_cache = false;        // set by LoadMeshCached (soup_cache.h)
  // Non-fatal cache problem (invalid cache rebuilt, cache not writable); empty
  // when none. Set by LoadMeshCached only.
  std::string cache_warning;
};

// Coordinates with a larger magnitude are treated as garbage.
inline constexpr float kMaxAbsCoordinate = 1e30f;

// Loads `path`, opened once (mesh_input.h): a regular file, a pipe or a
// process substitution. A name ending in ".gz" (any case) is decompressed in
// memory and parsed with the inner extension as the format hint
// ("x.ply.gz" -> "ply"). Errors name the file and the reason: missing, a
// directory or device, over the input budget, unreadable, corrupt gzip,
// assimp's error string, or no triangles left. Never aborts on bad input.
absl::StatusOr<TriangleSoup> LoadMesh(const std::string& path, LoadReport* report = nullptr,
                                      const LoadOptions& options = LoadOptions());

// True when the triangle has zero area in exact arithmetic (its vertices are
// collinear or coincide). Inputs must be finite with |c| <= kMaxAbsCoordinate.
bool IsDegenerateTriangle(const Vec3& a, const Vec3& b, const Vec3& c);

// True when all coordinates are finite and at most kMaxAbsCoordinate in size.
bool IsSaneTriangle(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace kdtree

#endif  // KDTREE_CC_IO_MESH_LOADER_H_
