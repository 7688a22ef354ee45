#include "cc/io/soup_cache.h"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <new>
#include <type_traits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cc/base/fnv.h"

namespace kdtree {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(float) && std::is_trivially_copyable_v<Vec3>,
              "the cache reads and writes Vec3 arrays as raw float32 triples");
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the cache format is little-endian");

constexpr char kMagic[8] = {'K', 'D', 'T', 'R', 'I', 'S', '0', '1'};
constexpr size_t kHeaderBytes = 16;  // magic + count
constexpr size_t kTriangleBytes = 9 * sizeof(float);
// Bump when the loader's output for the same file may change.
constexpr int kCacheKeyVersion = 1;
constexpr char kMetaTag[] = "KDTRISMETA1";

uint64_t FnvString(const std::string& s) { return FnvBytes(s.data(), s.size()); }

// Asks for transparent huge pages on a large fresh allocation: page faults,
// not copying, dominate reading a big cache otherwise. Advisory only.
void AdviseHugePages(void* data, size_t bytes) {
  constexpr uintptr_t kHuge = uintptr_t{2} << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// True when every float has |x| <= kMaxAbsCoordinate (so no NaN or Inf);
// compares magnitude bits so that the loop vectorizes.
bool AllCoordinatesSane(const void* data, size_t n_floats) {
  uint32_t limit;
  std::memcpy(&limit, &kMaxAbsCoordinate, 4);
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint32_t worst = 0;
  for (size_t i = 0; i < n_floats; ++i) {
    uint32_t bits;
    std::memcpy(&bits, p + 4 * i, 4);
    bits &= 0x7fffffffu;
    worst = bits > worst ? bits : worst;
  }
  return worst <= limit;
}

// Writes through `write` into a unique temporary file beside `path`, then
// renames it over `path`.
absl::Status WriteAtomically(const std::string& path,
                             const std::function<bool(std::FILE*)>& write) {
  static std::atomic<uint64_t> counter{0};
  const std::string tmp = absl::StrCat(path, ".tmp.", ::getpid(), ".", counter++);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) {
    return FileError(absl::StatusCode::kUnavailable, path,
                     absl::StrCat("cannot create temporary file ", tmp, ": ",
                                  std::strerror(errno)));
  }
  const bool wrote = write(f);
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!wrote || !closed) {
    std::remove(tmp.c_str());
    return FileError(absl::StatusCode::kUnavailable, path,
                     absl::StrCat("write failed: ", std::strerror(wrote ? errno : write_errno)));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    return FileError(absl::StatusCode::kUnavailable, path,
                     absl::StrCat("cannot rename ", tmp, " into place: ", std::strerror(err)));
  }
  return absl::OkStatus();
}

std::string MetaPath(const std::string& cache_path) {
  return cache_path.substr(0, cache_path.size() - 5) + ".meta";  // "x.tris" -> "x.meta"
}

absl::Status WriteMeta(const std::string& path, const LoadReport& r) {
  const std::string text = absl::StrFormat("%s %d %d %d %d\n", kMetaTag, r.triangles,
                                           r.skipped_faces, r.dropped_degenerate,
                                           r.dropped_nonfinite);
  return WriteAtomically(path, [&text](std::FILE* f) {
    return std::fwrite(text.data(), 1, text.size(), f) == text.size();
  });
}

// Reads the counts written by WriteMeta; false when missing or malformed.
bool ReadMeta(const std::string& path, LoadReport* r) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  char tag[16] = {};
  unsigned long long n[4];
  const int got = std::fscanf(f, "%15s %llu %llu %llu %llu", tag, &n[0], &n[1], &n[2], &n[3]);
  std::fclose(f);
  if (got != 5 || std::strcmp(tag, kMetaTag) != 0) return false;
  r->triangles = n[0];
  r->skipped_faces = n[1];
  r->dropped_degenerate = n[2];
  r->dropped_nonfinite = n[3];
  return true;
}

// File name part of the mesh, restricted to a safe character set.
std::string SafeStem(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  if (name.size() > 64) name.resize(64);
  for (char& c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) c = '_';
  }
  return name.empty() ? "mesh" : name;
}

}  // namespace

uint64_t SoupChecksum(const void* data, size_t size) { return FnvWords(data, size); }

absl::Status WriteSoupCache(const std::string& path, const TriangleSoup& soup) {
  if (soup.v.size() % 3 != 0) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     absl::StrCat("soup has ", soup.v.size(), " vertices, not a multiple of 3"));
  }
  const uint64_t count = soup.size();
  const size_t bytes = count * kTriangleBytes;
  const uint64_t checksum = FnvWords(soup.v.data(), bytes, FnvWords(&count, 8));
  return WriteAtomically(path, [&](std::FILE* f) {
    return std::fwrite(kMagic, 1, 8, f) == 8 && std::fwrite(&count, 1, 8, f) == 8 &&
           (bytes == 0 || std::fwrite(soup.v.data(), 1, bytes, f) == bytes) &&
           std::fwrite(&checksum, 1, 8, f) == 8;
  });
}

absl::StatusOr<TriangleSoup> ReadSoupCache(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    return FileError(err == ENOENT ? absl::StatusCode::kNotFound : absl::StatusCode::kUnavailable,
                     path, absl::StrCat("cannot open triangle cache: ", std::strerror(err)));
  }
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  struct stat st;
  if (::fstat(::fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
    return FileError(absl::StatusCode::kInvalidArgument, path, "not a regular file");
  }
  const uint64_t file_size = static_cast<uint64_t>(st.st_size);
  char header[kHeaderBytes];
  if (file_size < kHeaderBytes + 8 || std::fread(header, 1, kHeaderBytes, f) != kHeaderBytes) {
    return FileError(absl::StatusCode::kDataLoss, path,
                     absl::StrCat("triangle cache truncated: only ", file_size, " bytes"));
  }
  if (std::memcmp(header, kMagic, 8) != 0) {
    return FileError(absl::StatusCode::kDataLoss, path,
                     "not a triangle cache (bad magic, expected \"KDTRIS01\")");
  }
  uint64_t count;
  std::memcpy(&count, header + 8, 8);
  const uint64_t max_count = (file_size - kHeaderBytes - 8) / kTriangleBytes;
  if (count > max_count || file_size != kHeaderBytes + count * kTriangleBytes + 8) {
    return FileError(absl::StatusCode::kDataLoss, path,
                     absl::StrCat("triangle cache truncated or corrupt: header says ", count,
                                  " triangles but the file has ", file_size, " bytes"));
  }
  TriangleSoup soup;
  try {
    soup.v.reserve(3 * count);
    AdviseHugePages(soup.v.data(), 3 * count * sizeof(Vec3));
    soup.v.resize(3 * count);
  } catch (const std::bad_alloc&) {
    return FileError(absl::StatusCode::kResourceExhausted, path,
                     absl::StrCat("out of memory for ", count, " triangles"));
  }
  const size_t bytes = count * kTriangleBytes;
  uint64_t stored = 0;
  if ((bytes != 0 && std::fread(soup.v.data(), 1, bytes, f) != bytes) ||
      std::fread(&stored, 1, 8, f) != 8) {
    return FileError(absl::StatusCode::kDataLoss, path, "short read: triangle cache truncated");
  }
  const uint64_t computed = FnvWords(soup.v.data(), bytes, FnvWords(&count, 8));
  if (stored != computed) {
    return FileError(absl::StatusCode::kDataLoss, path,
                     absl::StrFormat("triangle cache corrupt: checksum mismatch (stored %016x, "
                                     "computed %016x)",
                                     stored, computed));
  }
  if (!AllCoordinatesSane(soup.v.data(), 9 * count)) {
    return FileError(absl::StatusCode::kDataLoss, path,
                     "triangle cache holds a non-finite or absurd coordinate");
  }
  return soup;
}

absl::StatusOr<std::string> SoupCachePath(const std::string& mesh_path,
                                          const std::string& cache_dir,
                                          const LoadOptions& options) {
  struct stat st;
  if (::stat(mesh_path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      return FileError(absl::StatusCode::kNotFound, mesh_path, "file not found");
    }
    return FileError(absl::StatusCode::kUnavailable, mesh_path,
                     absl::StrCat("cannot stat file: ", std::strerror(err)));
  }
  std::error_code ec;
  std::filesystem::path abs = std::filesystem::weakly_canonical(mesh_path, ec);
  if (ec) abs = std::filesystem::absolute(mesh_path, ec).lexically_normal();
  if (ec) abs = mesh_path;
  const std::string key = absl::StrCat(
      "v", kCacheKeyVersion, "|", abs.string(), "|", static_cast<int64_t>(st.st_size), "|",
      static_cast<int64_t>(st.st_mtim.tv_sec), ".", static_cast<int64_t>(st.st_mtim.tv_nsec), "|",
      options.drop_degenerate ? "drop-degenerate" : "keep-degenerate");
  const std::string name = absl::StrFormat("%s-%016x.tris", SafeStem(mesh_path), FnvString(key));
  return (std::filesystem::path(cache_dir) / name).string();
}

absl::StatusOr<TriangleSoup> LoadMeshCached(const std::string& mesh_path,
                                            const std::string& cache_dir, LoadReport* report,
                                            const LoadOptions& options) {
  // Only a regular file has a size and time that say its bytes are the same;
  // a pipe or process substitution is loaded (once) and never cached.
  struct stat st;
  if (cache_dir.empty() || ::stat(mesh_path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    return LoadMesh(mesh_path, report, options);
  }
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  LoadReport local;
  LoadReport* r = report != nullptr ? report : &local;
  *r = LoadReport();

  absl::StatusOr<std::string> cache_path = SoupCachePath(mesh_path, cache_dir, options);
  if (!cache_path.ok()) return cache_path.status();
  const std::string meta_path = MetaPath(*cache_path);

  std::string warning;
  std::error_code ec;
  if (std::filesystem::exists(*cache_path, ec)) {
    absl::StatusOr<TriangleSoup> cached = ReadSoupCache(*cache_path);
    LoadReport meta;
    if (!cached.ok()) {
      warning = absl::StrCat("ignored invalid cache: ", cached.status().message());
    } else if (!ReadMeta(meta_path, &meta) || meta.triangles != cached->size()) {
      warning = absl::StrCat("ignored cache with missing or inconsistent ", meta_path);
    } else {
      *r = meta;
      r->from_cache = true;
      r->load_seconds = elapsed();
      return cached;
    }
  }

  absl::StatusOr<TriangleSoup> soup = LoadMesh(mesh_path, r, options);
  if (!soup.ok()) return soup;
  std::filesystem::create_directories(cache_dir, ec);
  absl::Status written = WriteSoupCache(*cache_path, *soup);
  if (written.ok()) written = WriteMeta(meta_path, *r);
  if (!written.ok()) {
    if (!warning.empty()) warning += "; ";
    warning += absl::StrCat("cache not written: ", written.message());
  }
  r->cache_warning = warning;
  r->load_seconds = elapsed();
  return soup;
}

}  // namespace kdtree
