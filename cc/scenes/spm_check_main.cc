// Parses every .spm file under a directory (spm.h) and reports how many do:
// the manual check of the reader against a whole SuperTuxKart data set.
//
//   bazel run -c opt //cc/scenes:spm_check --
//       --dir=/abs/data/cache/extracted/supertuxkart-data/usr/share/games/supertuxkart/data
//
// One line per failing file on stderr ("FAIL path: reason"), then one JSON
// line on stdout: files, parsed, failed, static, skinned, triangles,
// vertices. Exit code 1 when a file fails or none is found.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "cc/base/json_line.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/spm.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, dir, "", "directory searched recursively for *.spm files");

namespace kdtree {
namespace scenes {
namespace {

int Main() {
  const std::string dir = absl::GetFlag(FLAGS_dir);
  if (dir.empty()) {
    std::fprintf(stderr, "spm_check: --dir is required\n");
    return 2;
  }
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec) && it->path().extension() == ".spm") {
      files.push_back(it->path().string());
    }
  }
  if (ec) {
    std::fprintf(stderr, "spm_check: %s: %s\n", dir.c_str(), ec.message().c_str());
    return 1;
  }
  std::sort(files.begin(), files.end());
  long long parsed = 0, skinned = 0, triangles = 0, vertices = 0;
  for (const std::string& path : files) {
    SpmInfo info;
    absl::StatusOr<Mesh> mesh = ReadSpm(path, {}, &info);
    if (!mesh.ok()) {
      std::fprintf(stderr, "FAIL %s\n", std::string(mesh.status().message()).c_str());
      continue;
    }
    ++parsed;
    skinned += info.skinned;
    triangles += static_cast<long long>(mesh->TriangleCount());
    vertices += static_cast<long long>(mesh->vertices.size());
  }
  const long long total = static_cast<long long>(files.size());
  const nlohmann::ordered_json line = {{"files", total},
                                       {"parsed", parsed},
                                       {"failed", total - parsed},
                                       {"static", parsed - skinned},
                                       {"skinned", skinned},
                                       {"triangles", triangles},
                                       {"vertices", vertices}};
  std::printf("%s\n", JsonLine(line).c_str());
  return parsed == total && total > 0 ? 0 : 1;
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return kdtree::scenes::Main();
}
