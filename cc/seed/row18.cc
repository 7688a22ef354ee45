#include "cc/seed/row18.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"

namespace kdtree {

absl::StatusOr<std::string> MakeSuzanneWithBlender(const std::string& dir) {
  const std::string out = dir + "/suzanne.obj";
  // HOME inside `dir`: Blender may write its user configuration there.
  const std::string cmd = absl::StrCat(
      "HOME='", dir, "' blender -b --factory-startup --python-expr \"import bpy; "
      "bpy.ops.object.select_all(action='SELECT'); bpy.ops.object.delete(); "
      "bpy.ops.mesh.primitive_monkey_add(size=2, location=(0,0,0)); "
      "bpy.ops.wm.obj_export(filepath='", out, "')\" > '", dir, "/blender.log' 2>&1");
  const int rc = std::system(cmd.c_str());
  std::ifstream check(out);
  if (rc != 0 || !check) {
    return absl::UnavailableError(absl::StrCat(
        "could not make Suzanne with Blender (exit status ", rc, "; log in ", dir,
        "/blender.log); install it with experiments/setup.sh --with-blender"));
  }
  return out;
}

absl::StatusOr<std::vector<SeedRow>> ReadSeedRows(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open"));
  std::vector<std::string> header;
  std::vector<SeedRow> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells = absl::StrSplit(line, ',');
    if (header.empty()) {
      header = cells;
      if (header.size() < 3 || header[0] != "column" || header[1] != "preset") {
        return absl::InvalidArgumentError(absl::StrCat(path, ":", line_no, ": bad header"));
      }
      continue;
    }
    if (cells.size() != header.size()) {
      return absl::InvalidArgumentError(absl::StrCat(path, ":", line_no, ": expected ",
                                                     header.size(), " cells, got ", cells.size()));
    }
    SeedRow row{cells[0], cells[1], cells[2], {}};
    for (size_t i = 3; i < cells.size(); ++i) {
      if (!cells[i].empty()) row.values[header[i]] = cells[i];
    }
    rows.push_back(row);
  }
  if (rows.empty()) return absl::InvalidArgumentError(absl::StrCat(path, ": no rows"));
  return rows;
}

}  // namespace kdtree
