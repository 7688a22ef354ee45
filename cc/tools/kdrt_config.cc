#include "cc/tools/kdrt_config.h"

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "cc/kdtree/env_file.h"

namespace kdtree {
namespace {

std::string Stem(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = base.find_last_of('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  return base;
}

}  // namespace

absl::StatusOr<bool> ParseBoolFlag(const std::string& name, const std::string& value) {
  const std::string v = absl::AsciiStrToLower(value);
  if (v == "on" || v == "true" || v == "1" || v == "yes") return true;
  if (v == "off" || v == "false" || v == "0" || v == "no") return false;
  return absl::InvalidArgumentError(
      absl::StrCat("--", name, "=", value, ": expected on/off, true/false, 1/0 or yes/no"));
}

absl::StatusOr<ResolvedConfig> ResolveConfig(const ConfigFlags& flags) {
  ResolvedConfig r;
  if (!flags.preset.empty()) {
    absl::StatusOr<Config> preset = Preset(flags.preset);
    if (!preset.ok()) {
      std::string names;
      for (const std::string& n : PresetNames()) absl::StrAppend(&names, names.empty() ? "" : ", ", n);
      return absl::InvalidArgumentError(
          absl::StrCat("--preset=", flags.preset, ": ", preset.status().message(), " (one of ", names, ")"));
    }
    r.config = *preset;
    r.preset = flags.preset;
  }
  if (!flags.env.empty()) {
    absl::StatusOr<EnvResult> env = LoadEnvironmentFile(flags.env, r.config);
    if (!env.ok()) return env.status();
    r.config = env->config;
    r.skipped_blocks = env->skipped_blocks;
    r.env_path = flags.env;
  }
  auto int_flag = [&](const char* name, const std::string& value, int* out) -> absl::Status {
    if (value.empty()) return absl::OkStatus();
    int v;
    if (!absl::SimpleAtoi(value, &v)) {
      return absl::InvalidArgumentError(absl::StrCat("--", name, "=", value, ": not an integer"));
    }
    *out = v;
    r.overrides.push_back(absl::StrCat(name, "=", v));
    return absl::OkStatus();
  };
  auto bool_flag = [&](const char* name, const std::string& value, bool* out) -> absl::Status {
    if (value.empty()) return absl::OkStatus();
    absl::StatusOr<bool> b = ParseBoolFlag(name, value);
    if (!b.ok()) return b.status();
    *out = *b;
    r.overrides.push_back(absl::StrCat(name, "=", *b ? "on" : "off"));
    return absl::OkStatus();
  };
  Config& c = r.config;
  for (absl::Status st : {int_flag("max_depth", flags.max_depth, &c.max_depth),
                          int_flag("max_leaf_size", flags.max_leaf_size, &c.max_leaf_size),
                          int_flag("bins", flags.bins, &c.bins),
                          bool_flag("binning", flags.binning, &c.use_binning),
                          bool_flag("driving_axis", flags.driving_axis, &c.use_driving_axis),
                          bool_flag("clipping", flags.clipping, &c.use_clipping),
                          bool_flag("pruning", flags.pruning, &c.use_pruning),
                          bool_flag("shadows", flags.shadows, &c.cast_shadow_rays),
                          bool_flag("seed_compatible", flags.seed_compatible, &c.seed_compatible)}) {
    if (!st.ok()) return st;
  }
  absl::Status valid = c.Validate();
  if (!valid.ok()) return valid;
  if (!flags.label.empty()) {
    r.label = flags.label;
  } else {
    r.label = r.preset.empty() ? "default" : r.preset;
    if (!r.env_path.empty() && Stem(r.env_path) != r.preset) {
      absl::StrAppend(&r.label, "+", Stem(r.env_path));
    }
    if (!r.overrides.empty()) absl::StrAppend(&r.label, "+custom");
  }
  return r;
}

}  // namespace kdtree
