#include "cc/kdtree/config.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace kdtree {

absl::Status Config::Validate() const {
  if (max_depth < 0 || max_depth > 60) {
    return absl::InvalidArgumentError(
        absl::StrCat("maxDepth must be in [0, 60], got ", max_depth));
  }
  if (max_leaf_size < 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("maxLeafSize must be >= 0, got ", max_leaf_size));
  }
  if (use_binning && (bins < 2 || bins > 65536)) {
    return absl::InvalidArgumentError(absl::StrCat("bins must be in [2, 65536], got ", bins));
  }
  return absl::OkStatus();
}

std::string Config::ToEnvironment() const {
  auto on = [](bool b) { return b ? "ON" : "OFF"; };
  return absl::StrFormat(
      "RTCore {\n    castShadowRays %s\n}\n\nKDTree {\n    maxDepth %d\n    maxLeafSize %d\n"
      "    Binning {\n        useBinning %s\n        useDrivingAxis %s\n        bins %d\n    }\n"
      "    useClipping %s\n    usePruning %s\n    seedCompatible %s\n}\n",
      on(cast_shadow_rays), max_depth, max_leaf_size, on(use_binning), on(use_driving_axis), bins,
      on(use_clipping), on(use_pruning), on(seed_compatible));
}

bool Config::operator==(const Config& o) const {
  return max_depth == o.max_depth && max_leaf_size == o.max_leaf_size &&
         use_binning == o.use_binning && use_driving_axis == o.use_driving_axis &&
         bins == o.bins && use_clipping == o.use_clipping && use_pruning == o.use_pruning &&
         cast_shadow_rays == o.cast_shadow_rays && seed_compatible == o.seed_compatible;
}

const std::vector<std::string>& PresetNames() {
  static const auto* names = new std::vector<std::string>{
      "median-16-2", "median-24-2", "median-24-8",      "binning-8-driving", "binning-8",
      "binning-32",  "clipping",    "pruning",          "clipping-pruning"};
  return *names;
}

namespace {
Config Median(int depth, int leaf) {
  Config c;
  c.max_depth = depth;
  c.max_leaf_size = leaf;
  c.use_binning = false;
  c.use_clipping = false;
  c.use_pruning = false;
  return c;
}
Config Binning(int bins, bool driving) {
  Config c;
  c.max_depth = 24;
  c.max_leaf_size = 8;
  c.use_binning = true;
  c.use_driving_axis = driving;
  c.bins = bins;
  c.use_clipping = false;
  c.use_pruning = false;
  return c;
}
}  // namespace

absl::StatusOr<Config> Preset(const std::string& name) {
  if (name == "median-16-2") return Median(16, 2);
  if (name == "median-24-2") return Median(24, 2);
  if (name == "median-24-8") return Median(24, 8);
  if (name == "binning-8-driving") return Binning(8, true);
  if (name == "binning-8") return Binning(8, false);
  if (name == "binning-32") return Binning(32, false);
  Config c = Binning(8, true);
  if (name == "clipping") {
    c.use_clipping = true;
    return c;
  }
  if (name == "pruning") {
    c.use_pruning = true;
    return c;
  }
  if (name == "clipping-pruning") {
    c.use_clipping = c.use_pruning = true;
    return c;
  }
  if (name == "pruning-seed") {
    Config p = Binning(32, false);
    p.use_pruning = true;
    p.seed_compatible = true;
    return p;
  }
  return absl::NotFoundError(absl::StrCat("unknown preset '", name, "'; known: ",
                                          "median-16-2, median-24-2, median-24-8, ",
                                          "binning-8-driving, binning-8, binning-32, clipping, ",
                                          "pruning, clipping-pruning, pruning-seed"));
}

}  // namespace kdtree
