// kdrt's kd-tree configuration from its flags: a preset (the report's nine
// columns, config.h), then an environment file applied on top of it
// (env_file.h), then single-option flags overriding both. Option flags are
// strings where "" means "not given".
#ifndef KDTREE_CC_TOOLS_KDRT_CONFIG_H_
#define KDTREE_CC_TOOLS_KDRT_CONFIG_H_

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/kdtree/config.h"

namespace kdtree {

struct ConfigFlags {
  std::string preset = "clipping-pruning";  // "" = start from Config() defaults
  std::string env;                          // environment file path, "" = none
  // Overrides ("" = not given). Integers, or booleans: on/off, true/false, 1/0, yes/no.
  std::string max_depth, max_leaf_size, bins;
  std::string binning, driving_axis, clipping, pruning, shadows, seed_compatible;
  std::string label;  // name for output files; "" = derived (see ResolvedConfig)
};

struct ResolvedConfig {
  Config config;
  std::string preset;    // the preset used ("" = none)
  std::string env_path;  // the environment file used ("" = none)
  std::vector<std::string> skipped_blocks;  // from the environment file
  std::vector<std::string> overrides;       // "max_depth=20", ... in flag order
  // flags.label, else preset (or "default"), then "+<env file stem>" with an
  // environment file whose stem is not the preset's name (run_matrix.py passes
  // --preset X --env presets/X.env), then "+custom" when any option flag was
  // given.
  std::string label;
};

absl::StatusOr<ResolvedConfig> ResolveConfig(const ConfigFlags& flags);

// "on"/"true"/"1"/"yes" and "off"/"false"/"0"/"no", any case.
absl::StatusOr<bool> ParseBoolFlag(const std::string& name, const std::string& value);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_CONFIG_H_
