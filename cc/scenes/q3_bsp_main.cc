// Converts a Quake 3 map (.bsp, IBSP 46) into binary PLY with our reader
// (cc/scenes/q3_bsp.h). Used by data/fetch.py (convert: q3-bsp) on the map
// it takes out of a game's .pk3.
//
//   bazel run -c opt //cc/scenes:q3_bsp_tool -- --bsp=/abs/map.bsp --out=/abs/map.ply
//
// Prints one JSON line: triangles, vertices, faces, kept/skipped faces, bounds.
#include <cstdio>
#include <string>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "cc/base/read_file.h"
#include "cc/base/json_line.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "cc/scenes/q3_bsp.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, bsp, "", "input .bsp file");
ABSL_FLAG(std::string, out, "", "output .ply file");
ABSL_FLAG(int, patch_subdivisions, kdtree::scenes::Q3BspConfig().patch_subdivisions,
          "quads per side of each Bezier patch");
ABSL_FLAG(bool, skip_sky, true, "skip sky surfaces");
ABSL_FLAG(bool, skip_nodraw, true, "skip nodraw surfaces");

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  const std::string in = absl::GetFlag(FLAGS_bsp), out = absl::GetFlag(FLAGS_out);
  if (in.empty() || out.empty()) {
    std::fprintf(stderr, "q3_bsp: --bsp and --out are required\n");
    return 2;
  }
  const absl::StatusOr<std::string> read = kdtree::ReadTextInput(in, "map", kdtree::scenes::kSceneInputBudget);
  if (!read.ok()) {
    std::fprintf(stderr, "q3_bsp: %s\n", std::string(read.status().message()).c_str());
    return 1;
  }
  const std::string& bytes = *read;
  kdtree::scenes::Q3BspConfig config;
  config.patch_subdivisions = absl::GetFlag(FLAGS_patch_subdivisions);
  config.skip_sky = absl::GetFlag(FLAGS_skip_sky);
  config.skip_nodraw = absl::GetFlag(FLAGS_skip_nodraw);
  kdtree::scenes::Q3BspStats stats;
  absl::StatusOr<kdtree::scenes::Mesh> mesh = kdtree::scenes::ParseQ3Bsp(bytes, config, &stats);
  if (!mesh.ok()) {
    std::fprintf(stderr, "q3_bsp: %s: %s\n", in.c_str(), mesh.status().ToString().c_str());
    return 1;
  }
  if (mesh->faces.empty()) {
    std::fprintf(stderr, "q3_bsp: %s: no drawn triangles\n", in.c_str());
    return 1;
  }
  if (absl::Status s = kdtree::scenes::WritePly(out, *mesh); !s.ok()) {
    std::fprintf(stderr, "q3_bsp: %s\n", s.ToString().c_str());
    return 1;
  }
  const kdtree::AABB b = mesh->Bounds();
  const nlohmann::ordered_json line = {
      {"triangles", mesh->TriangleCount()},
      {"vertices", mesh->vertices.size()},
      {"faces", static_cast<long long>(stats.faces)},
      {"polygon_faces", static_cast<long long>(stats.polygon_faces)},
      {"patch_faces", static_cast<long long>(stats.patch_faces)},
      {"skipped_faces", static_cast<long long>(stats.skipped_faces)},
      {"bounds", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}}};
  std::printf("%s\n", kdtree::JsonLine(line).c_str());
  return 0;
}
