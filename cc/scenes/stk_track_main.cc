// Converts one SuperTuxKart track (stk_track.h) into a binary PLY.
//
//   bazel run -c opt //cc/scenes:stk_track --
//       --track_dir=/abs/.../supertuxkart/data/tracks/black_forest --out=/abs/black_forest.ply
//
// Prints one JSON line: triangles, vertices, meshes placed, LOD instances,
// libraries, distinct models, skipped objects by reason, bounds, seconds.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/str_split.h"
#include "cc/base/json_line.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "cc/scenes/stk_track.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, track_dir, "", "the track's directory (holding scene.xml)");
ABSL_FLAG(std::string, data_dir, "", "STK data directory (library/, models/); default: "
                                     "two levels above --track_dir");
ABSL_FLAG(std::string, out, "", "output .ply path (absolute under bazel run)");
ABSL_FLAG(bool, reverse, false, "evaluate `if` conditions for the reverse direction");
ABSL_FLAG(bool, all_conditions, false, "keep objects whatever their `if` condition");
ABSL_FLAG(std::string, skip_interactions, "physics-only,physicsonly",
          "comma-separated `interaction` values of objects not drawn (collision-only)");
ABSL_FLAG(bool, left_handed, false, "keep the game's left-handed frame (z not negated)");

namespace kdtree {
namespace scenes {
namespace {

int Main() {
  const std::string track_dir = absl::GetFlag(FLAGS_track_dir), out = absl::GetFlag(FLAGS_out);
  if (track_dir.empty() || out.empty()) {
    std::fprintf(stderr, "stk_track: --track_dir and --out are required\n");
    return 2;
  }
  StkTrackOptions options;
  options.data_dir = absl::GetFlag(FLAGS_data_dir);
  options.reverse = absl::GetFlag(FLAGS_reverse);
  options.evaluate_conditions = !absl::GetFlag(FLAGS_all_conditions);
  options.skip_interactions =
      absl::StrSplit(absl::GetFlag(FLAGS_skip_interactions), ',', absl::SkipEmpty());
  options.right_handed = !absl::GetFlag(FLAGS_left_handed);
  const auto start = std::chrono::steady_clock::now();
  StkTrackStats stats;
  absl::StatusOr<Mesh> mesh = ReadStkTrack(track_dir, options, &stats);
  if (!mesh.ok()) {
    std::fprintf(stderr, "stk_track: %s\n", mesh.status().ToString().c_str());
    return 1;
  }
  if (absl::Status s = WritePly(out, *mesh); !s.ok()) {
    std::fprintf(stderr, "stk_track: %s\n", s.ToString().c_str());
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::ordered_json skipped = nlohmann::ordered_json::object();
  for (const auto& [reason, count] : stats.skipped) skipped[reason] = count;
  const AABB b = mesh->Bounds();
  const nlohmann::ordered_json line = {
      {"triangles", mesh->TriangleCount()},
      {"vertices", mesh->vertices.size()},
      {"placed", static_cast<long long>(stats.placed)},
      {"lod_instances", static_cast<long long>(stats.lod_instances)},
      {"libraries", static_cast<long long>(stats.libraries)},
      {"models", static_cast<long long>(stats.models)},
      {"skipped", skipped},
      {"bounds", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
      {"seconds", seconds}};
  std::printf("%s\n", JsonLine(line).c_str());
  return 0;
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return kdtree::scenes::Main();
}
