// Loads one mesh (optionally through the triangle cache) and prints one line
// of JSON: counts, bounds and load time.
//
//   bazel run -c opt //cc/tools:scene_info -- --mesh=/path/bunny.obj
//     --cache_dir=/tmp/cache --name=bunny
//   {"scene": "bunny", "mesh": "/path/bunny.obj", "n_tri": 69666, ...}
//
// On error the status message goes to stderr and the exit code is 1.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "cc/base/json_line.h"
#include "cc/geometry/aabb.h"
#include "cc/geometry/triangle.h"
#include "cc/io/mesh_loader.h"
#include "cc/io/soup_cache.h"
#include "cc/tools/paths.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, mesh, "", "Mesh file to load (anything assimp reads, or .gz of it).");
ABSL_FLAG(std::string, cache_dir, "", "Triangle-cache directory; empty = no cache.");
ABSL_FLAG(std::string, name, "", "Scene name, echoed in the output.");

namespace kdtree {
namespace {

int Run(const std::vector<char*>& positional) {
  if (positional.size() > 1) {
    std::fprintf(stderr, "scene_info: unexpected argument '%s'\n", positional[1]);
    return 1;
  }
  const std::string mesh = absl::GetFlag(FLAGS_mesh);
  if (mesh.empty()) {
    std::fprintf(stderr, "scene_info: --mesh is required\n");
    return 1;
  }
  const std::string mesh_path = FromInvocationDir(mesh);
  const std::string cache_dir = FromInvocationDir(absl::GetFlag(FLAGS_cache_dir));

  LoadReport report;
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(mesh_path, cache_dir, &report);
  if (!soup.ok()) {
    std::fprintf(stderr, "scene_info: %s\n", std::string(soup.status().message()).c_str());
    return 1;
  }
  if (!report.cache_warning.empty()) {
    std::fprintf(stderr, "scene_info: warning: %s\n", report.cache_warning.c_str());
  }
  const AABB box = soup->Bounds();
  using Json = nlohmann::ordered_json;
  const Json line = {{"scene", absl::GetFlag(FLAGS_name)},
                     {"mesh", mesh},
                     {"n_tri", soup->size()},
                     {"skipped_faces", report.skipped_faces},
                     {"dropped_degenerate", report.dropped_degenerate},
                     {"dropped_nonfinite", report.dropped_nonfinite},
                     {"load_s", report.load_seconds},
                     {"from_cache", report.from_cache},
                     {"bounds", {{box.lo.x, box.lo.y, box.lo.z}, {box.hi.x, box.hi.y, box.hi.z}}}};
  std::printf("%s\n", JsonLine(line).c_str());
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace
}  // namespace kdtree

int main(int argc, char** argv) {
  std::vector<char*> positional = absl::ParseCommandLine(argc, argv);
  return kdtree::Run(positional);
}
