// Prints our seed-compatible statistics for each column of the report's row 18,
// one JSON line per column, for the analysis to put next to the report's.
//   bazel run //cc/seed:row18_tool -- --mesh data/cache/scenes/suzanne.obj
#include <cstdio>
#include <string>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "cc/base/json_line.h"
#include "cc/io/mesh_loader.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/stats.h"
#include "cc/seed/row18.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, mesh, "", "Suzanne mesh (empty: make it with Blender in --work_dir)");
ABSL_FLAG(std::string, work_dir, "/tmp", "where Blender writes suzanne.obj");
ABSL_FLAG(std::string, expected, "data/seed/row18.csv", "the report's row 18");

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  std::string mesh = absl::GetFlag(FLAGS_mesh);
  if (mesh.empty()) {
    absl::StatusOr<std::string> made = kdtree::MakeSuzanneWithBlender(absl::GetFlag(FLAGS_work_dir));
    if (!made.ok()) {
      std::fprintf(stderr, "%s\n", made.status().ToString().c_str());
      return 1;
    }
    mesh = *made;
  }
  absl::StatusOr<kdtree::TriangleSoup> soup = kdtree::LoadMesh(mesh);
  absl::StatusOr<std::vector<kdtree::SeedRow>> rows =
      kdtree::ReadSeedRows(absl::GetFlag(FLAGS_expected));
  if (!soup.ok() || !rows.ok()) {
    std::fprintf(stderr, "%s\n",
                 (!soup.ok() ? soup.status() : rows.status()).ToString().c_str());
    return 1;
  }
  for (const kdtree::SeedRow& row : *rows) {
    for (const bool seed : {true, false}) {
      kdtree::Config c = *kdtree::Preset(seed ? row.seed_preset : row.preset);
      c.seed_compatible = seed;
      absl::StatusOr<kdtree::KdTree> tree = kdtree::BuildKdTree(*soup, c);
      if (!tree.ok()) {
        std::fprintf(stderr, "%s\n", tree.status().ToString().c_str());
        return 1;
      }
      const nlohmann::ordered_json line = {
          {"column", row.column},
          {"preset", seed ? row.seed_preset : row.preset},
          {"mode", seed ? "seed" : "default"},
          {"n_tri", soup->size()},
          {"stats", kdtree::StatsToJson(kdtree::ComputeStats(*tree))}};
      std::printf("%s\n", kdtree::JsonLine(line).c_str());
    }
  }
  return 0;
}
