#include "cc/io/mesh_fuzz.h"

#include <zlib.h>

#include <unistd.h>

#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "cc/io/mesh_loader.h"
#include "cc/io/mesh_syntax.h"

namespace kdtree {

const char* FuzzFormat(uint8_t selector) {
  // 3: the bytes gzip-compressed (the loader inflates, then parses them);
  // 4: the bytes as they are under a .gz name (inflating arbitrary bytes).
  static const char* const kFormats[] = {"obj", "off", "ply", "obj.gz", "ply.gz"};
  return kFormats[selector % 5];
}

size_t MeshFuzzCase(const uint8_t* data, size_t size, const std::string& tmp_dir) {
  if (size == 0) return 0;
  const std::string format = FuzzFormat(data[0]);
  const absl::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string inner = format.substr(0, format.find('.'));
  (void)CheckMeshSyntax(bytes, inner, "fuzz");  // must not crash on its own
  const std::string path = absl::StrCat(tmp_dir, "/mesh_fuzz_", getpid(), ".", format);
  if (format == "obj.gz") {
    gzFile gz = gzopen(path.c_str(), "wb");
    if (gz == nullptr) return 1;
    const bool written = bytes.empty() ||
                         gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size())) > 0;
    if (gzclose(gz) != Z_OK || !written) return 1;
  } else {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) return 1;
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    std::fclose(f);
    if (!written) return 1;
  }
  LoadReport report;
  const absl::StatusOr<TriangleSoup> soup = LoadMesh(path, &report);
  std::remove(path.c_str());
  if (!soup.ok()) return soup.status().message().find(path) == absl::string_view::npos;
  size_t broken = report.triangles != soup->size();
  for (size_t i = 0; i < soup->size(); ++i) {
    broken += !IsSaneTriangle(soup->a(i), soup->b(i), soup->c(i)) ||
              IsDegenerateTriangle(soup->a(i), soup->b(i), soup->c(i));
  }
  return broken;
}

}  // namespace kdtree
