#include "cc/kdtree/config.h"

#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"

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
  if (split_method != SplitMethod::kBinned && !use_binning) {
    return absl::InvalidArgumentError("splitMethod sweep/hybrid needs useBinning ON");
  }
  if (hybrid_bins < 2 || hybrid_bins > 65536 || hybrid_threshold < 0) {
    return absl::InvalidArgumentError(absl::StrCat("hybridBins must be in [2, 65536] and ",
                                                   "hybridThreshold >= 0, got ", hybrid_bins,
                                                   ", ", hybrid_threshold));
  }
  if (perfect_splits && !use_clipping) {
    return absl::InvalidArgumentError("perfectSplits needs useClipping ON");
  }
  if (perfect_splits && seed_compatible) {
    return absl::InvalidArgumentError("perfectSplits is not part of the seed-compatible mode");
  }
  if (!(traversal_cost >= 0) || !(intersection_cost > 0) || !(empty_bonus > 0) ||
      empty_bonus > 1) {
    return absl::InvalidArgumentError("SAH constants: K_T >= 0, K_I > 0, 0 < bonus <= 1");
  }
  if (sah_packet < 1 || sah_packet > 64) {
    return absl::InvalidArgumentError(absl::StrCat("sahPacket must be in [1, 64], got ", sah_packet));
  }
  if (build_threads < 0) {
    return absl::InvalidArgumentError(absl::StrCat("buildThreads must be >= 0, got ", build_threads));
  }
  return absl::OkStatus();
}

std::string Config::ToEnvironment() const {
  auto on = [](bool b) { return b ? "ON" : "OFF"; };
  // Options beyond the report are written only when they differ from the
  // defaults, so that the report's presets print exactly as before.
  const Config d;
  std::string extra;
  if (full_sah != d.full_sah) absl::StrAppend(&extra, "    fullSah ", on(full_sah), "\n");
  if (traversal_cost != d.traversal_cost) {
    absl::StrAppend(&extra, "    traversalCost ", absl::StrFormat("%.17g", traversal_cost), "\n");
  }
  if (intersection_cost != d.intersection_cost) {
    absl::StrAppend(&extra, "    intersectionCost ", absl::StrFormat("%.17g", intersection_cost),
                    "\n");
  }
  if (empty_bonus != d.empty_bonus) {
    absl::StrAppend(&extra, "    emptyBonus ", absl::StrFormat("%.17g", empty_bonus), "\n");
  }
  if (auto_depth != d.auto_depth) absl::StrAppend(&extra, "    autoDepth ", on(auto_depth), "\n");
  if (split_method != d.split_method) {
    absl::StrAppend(&extra, "    splitMethod ", SplitMethodName(split_method), "\n");
  }
  if (hybrid_bins != d.hybrid_bins) absl::StrAppend(&extra, "    hybridBins ", hybrid_bins, "\n");
  if (hybrid_threshold != d.hybrid_threshold) {
    absl::StrAppend(&extra, "    hybridThreshold ", hybrid_threshold, "\n");
  }
  if (perfect_splits != d.perfect_splits) {
    absl::StrAppend(&extra, "    perfectSplits ", on(perfect_splits), "\n");
  }
  if (exact_pruning != d.exact_pruning) {
    absl::StrAppend(&extra, "    exactPruning ", on(exact_pruning), "\n");
  }
  if (collapse != d.collapse) absl::StrAppend(&extra, "    collapse ", on(collapse), "\n");
  if (sah_packet != d.sah_packet) absl::StrAppend(&extra, "    sahPacket ", sah_packet, "\n");
  if (build_threads != d.build_threads) {
    absl::StrAppend(&extra, "    buildThreads ", build_threads, "\n");
  }
  std::string env = absl::StrFormat(
      "RTCore {\n    castShadowRays %s\n}\n\nKDTree {\n    maxDepth %d\n    maxLeafSize %d\n"
      "    Binning {\n        useBinning %s\n        useDrivingAxis %s\n        bins %d\n    }\n"
      "    useClipping %s\n    usePruning %s\n    seedCompatible %s\n}\n",
      on(cast_shadow_rays), max_depth, max_leaf_size, on(use_binning), on(use_driving_axis), bins,
      on(use_clipping), on(use_pruning), on(seed_compatible));
  env.insert(env.size() - 2, extra);  // before the KDTree block's closing "}\n"
  return env;
}

bool Config::operator==(const Config& o) const {
  return max_depth == o.max_depth && max_leaf_size == o.max_leaf_size &&
         use_binning == o.use_binning && use_driving_axis == o.use_driving_axis &&
         bins == o.bins && use_clipping == o.use_clipping && use_pruning == o.use_pruning &&
         cast_shadow_rays == o.cast_shadow_rays && seed_compatible == o.seed_compatible &&
         full_sah == o.full_sah && traversal_cost == o.traversal_cost &&
         intersection_cost == o.intersection_cost && empty_bonus == o.empty_bonus &&
         auto_depth == o.auto_depth && split_method == o.split_method &&
         hybrid_bins == o.hybrid_bins && hybrid_threshold == o.hybrid_threshold &&
         perfect_splits == o.perfect_splits && exact_pruning == o.exact_pruning &&
         collapse == o.collapse && sah_packet == o.sah_packet &&
         build_threads == o.build_threads;
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

// Beyond the report: the full SAH of Wald & Havran 2006 (config.h), the
// presets named sah-*; nullopt for any other name.
std::optional<Config> SahPreset(const std::string& name) {
  Config s = Binning(32, false);
  s.max_leaf_size = 1;
  s.full_sah = true;
  s.auto_depth = true;
  if (name == "sah-binned-32") return s;
  if (name == "sah-packet-binned" || name == "sah-packet-binned-cp") {
    // sah-packet's cost model (packets of 4, K_T 45) with the report's
    // cheapest split search, 16 bins on the driving axis only: the fast
    // builds. The cost termination stops where a packet of 4 no longer pays
    // for a level, so the trees hold a sixth to a quarter of
    // binning-8-driving's nodes and 40-50 % of its references, and most
    // levels of the build see fewer. Measured (build_bench, one thread):
    // 1.2-1.9x faster builds than binning-8-driving on the five scenes of
    // 1.5-2.9 M triangles, about as fast on asian-dragon (7.2 M, a dense
    // scan: 2 references per triangle, 25 levels on average); renders
    // 1.24-1.49x faster on bunny, rungholt-1m and hairball-1m (render_bench
    // --envs, same rays). -cp adds the report's clipping and pruning.
    s.use_driving_axis = true;
    s.bins = 16;
    s.sah_packet = 4;
    s.traversal_cost = 45.0;
    s.use_clipping = s.use_pruning = name == "sah-packet-binned-cp";
    return s;
  }
  s.use_clipping = s.use_pruning = true;
  if (name == "sah-sweep") {
    s.split_method = Config::SplitMethod::kSweep;
    return s;
  }
  s.split_method = Config::SplitMethod::kHybrid;
  if (name == "sah-hybrid") return s;
  if (name == "sah-packet") {
    // K_T 45 (K_I 20): tuned with render_bench --envs, sweeps of K_T 10-90
    // on 8 scenes, re-checked with paired ratios (per round, 7 rounds, a
    // control tree at 0.999): K_T 15 renders at 0.95x of K_T 45's speed,
    // 30 at 1.01x (a plateau with 45), 60 at 0.98x. A leaf of up to 4
    // references costs one packet test, so a step down the tree is worth
    // about two of them.
    s.sah_packet = 4;
    s.traversal_cost = 45.0;
    return s;
  }
  if (name == "sah-perfect") {
    s.perfect_splits = true;
    s.collapse = true;
    return s;
  }
  return std::nullopt;
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
  if (std::optional<Config> s = SahPreset(name)) return *s;
  if (name == "pruning-seed") {
    Config p = Binning(32, false);
    p.use_pruning = true;
    p.seed_compatible = true;
    return p;
  }
  return absl::NotFoundError(absl::StrCat("unknown preset '", name,
                                          "'; known: ", absl::StrJoin(KnownPresetNames(), ", ")));
}

const std::vector<std::string>& ExtraPresetNames() {
  static const auto* names =
      new std::vector<std::string>{"sah-binned-32", "sah-sweep", "sah-hybrid", "sah-perfect",
                                   "sah-packet", "sah-packet-binned", "sah-packet-binned-cp"};
  return *names;
}

std::vector<std::string> KnownPresetNames() {
  std::vector<std::string> known = PresetNames();
  known.push_back("pruning-seed");
  known.insert(known.end(), ExtraPresetNames().begin(), ExtraPresetNames().end());
  return known;
}

std::vector<std::string> AllPresetNames() {
  std::vector<std::string> all = PresetNames();
  all.insert(all.end(), ExtraPresetNames().begin(), ExtraPresetNames().end());
  return all;
}

const char* SplitMethodName(Config::SplitMethod m) {
  switch (m) {
    case Config::SplitMethod::kSweep:
      return "sweep";
    case Config::SplitMethod::kHybrid:
      return "hybrid";
    case Config::SplitMethod::kBinned:
      break;
  }
  return "binned";
}

}  // namespace kdtree
