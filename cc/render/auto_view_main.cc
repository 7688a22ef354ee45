// Prints the default camera and light of a scene from its bounds: the framing
// rule of cc/render/framing.h, in the form data/manifest.json stores it. To
// add a scene to the manifest, give it the scene's measured bounds (fetch.py
// writes them to data/cache/scenes/index.json), its up axis and framing:
//
//   bazel run //cc/render:auto_view -- --bounds=-1,-1,-1,1,1,1 --up_axis=1 --framing=object
//   {"camera":{"position":[...],"look_at":[...],"up":[...],"fov_deg":45.0},"light":{"position":[...]}}
//
// data/manifest_test.py checks every manifest camera against it.
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "cc/base/json_line.h"
#include "cc/render/framing.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, bounds, "", "lo_x,lo_y,lo_z,hi_x,hi_y,hi_z");
ABSL_FLAG(int, up_axis, 1, "1 (y up) or 2 (z up)");
ABSL_FLAG(std::string, framing, "object", "object (raised 15 degrees), landscape or interior (35)");

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  const std::vector<std::string> words = absl::StrSplit(absl::GetFlag(FLAGS_bounds), ',');
  double b[6];
  bool ok = words.size() == 6;
  for (size_t i = 0; ok && i < 6; ++i) ok = absl::SimpleAtod(words[i], &b[i]);
  if (!ok) {
    std::fprintf(stderr, "auto_view: --bounds wants six numbers, lo_x,lo_y,lo_z,hi_x,hi_y,hi_z\n");
    return 2;
  }
  const absl::StatusOr<kdtree::Framing> framing =
      kdtree::ParseFraming(absl::GetFlag(FLAGS_up_axis), absl::GetFlag(FLAGS_framing));
  if (!framing.ok()) {
    std::fprintf(stderr, "auto_view: %s\n", std::string(framing.status().message()).c_str());
    return 2;
  }
  const kdtree::FramedView v = kdtree::FrameBounds({b[0], b[1], b[2]}, {b[3], b[4], b[5]}, *framing);
  const nlohmann::ordered_json line = {
      {"camera",
       {{"position", v.position}, {"look_at", v.look_at}, {"up", v.up}, {"fov_deg", v.fov_deg}}},
      {"light", {{"position", v.light}}}};
  std::printf("%s\n", kdtree::JsonLine(line).c_str());
  return 0;
}
