// Binary triangle-soup cache: a 10M-triangle scene reloads in about a second.
//
// File format (all little-endian):
//   bytes [0, 8)            magic "KDTRIS01"
//   bytes [8, 16)           uint64 triangle count n
//   bytes [16, 16 + 36n)    9 float32 per triangle: a.xyz b.xyz c.xyz
//   last 8 bytes            uint64 checksum of bytes [8, 16 + 36n)
// Checksum: FNV-1a applied to 64-bit words instead of bytes: h starts at
// 0xcbf29ce484222325; for each little-endian uint64 word w of the checksummed
// range (the last word zero-padded when 36n is not a multiple of 8):
// h = (h ^ w) * 0x100000001b3 (mod 2^64). Any single changed word is detected.
//
// LoadMeshCached also keeps a small text file beside each cache file with the
// load counts of the original import (skipped/dropped), so a cached load
// reports the same numbers as the first one.
#ifndef KDTREE_CC_IO_SOUP_CACHE_H_
#define KDTREE_CC_IO_SOUP_CACHE_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"
#include "cc/io/mesh_loader.h"

namespace kdtree {

// The checksum described above, over `size` bytes.
uint64_t SoupChecksum(const void* data, size_t size);

// Writes `soup` to `path` atomically (temporary file in the same directory,
// then rename). Errors name the file.
absl::Status WriteSoupCache(const std::string& path, const TriangleSoup& soup);

// Reads a cache file. Wrong magic, wrong size (truncation), checksum mismatch
// and non-finite coordinates are errors naming the file.
absl::StatusOr<TriangleSoup> ReadSoupCache(const std::string& path);

// LoadMesh with a cache in `cache_dir` (created when missing; empty = no
// cache). The cache key is the mesh's absolute path, size and modification
// time (plus the load options). A valid cache entry is returned directly
// (report->from_cache = true); otherwise the mesh is loaded and the cache
// written. An invalid entry or an unwritable cache is not an error: the mesh is
// loaded and report->cache_warning says what happened. Anything but a regular
// file (a pipe, a process substitution) is loaded by LoadMesh, never cached.
absl::StatusOr<TriangleSoup> LoadMeshCached(const std::string& mesh_path,
                                            const std::string& cache_dir,
                                            LoadReport* report = nullptr,
                                            const LoadOptions& options = LoadOptions());

// The cache file LoadMeshCached uses for `mesh_path` (which must exist).
absl::StatusOr<std::string> SoupCachePath(const std::string& mesh_path,
                                          const std::string& cache_dir,
                                          const LoadOptions& options = LoadOptions());

}  // namespace kdtree

#endif  // KDTREE_CC_IO_SOUP_CACHE_H_
