// The report's scene 18: Blender's monkey, as Blender 3.4 makes it headless and
// assimp triangulates it (507 vertices, 968 triangles); and the report's
// expected row 18, read from data/seed/row18.csv.
#ifndef KDTREE_CC_SEED_ROW18_H_
#define KDTREE_CC_SEED_ROW18_H_

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"

namespace kdtree {

// Writes suzanne.obj into `dir` by running `blender` headless
// (--factory-startup; primitive_monkey_add(size=2); wm.obj_export) and returns
// its path. Errors name the command and its exit status.
absl::StatusOr<std::string> MakeSuzanneWithBlender(const std::string& dir);

// One column of the report's row 18. Fields the report does not print are absent.
struct SeedRow {
  std::string column;       // the report's column title
  std::string preset;       // our preset for that column
  std::string seed_preset;  // the preset that reproduces it in seed-compatible mode
  std::map<std::string, std::string> values;  // as printed: "N_I" -> "11717"
};

// Parses data/seed/row18.csv (lines starting with '#' are comments).
absl::StatusOr<std::vector<SeedRow>> ReadSeedRows(const std::string& path);

}  // namespace kdtree

#endif  // KDTREE_CC_SEED_ROW18_H_
