#include "cc/kdtree/config.h"

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Config, DefaultsEqualTheReportsEnvironmentFile) {
  const Config c;
  EXPECT_EQ(c.max_depth, 24);
  EXPECT_EQ(c.max_leaf_size, 4);
  EXPECT_TRUE(c.use_binning);
  EXPECT_TRUE(c.use_driving_axis);
  EXPECT_EQ(c.bins, 16);
  EXPECT_TRUE(c.use_clipping);
  EXPECT_TRUE(c.use_pruning);
  EXPECT_TRUE(c.cast_shadow_rays);
  EXPECT_FALSE(c.seed_compatible);
  EXPECT_TRUE(c.Validate().ok());
}

TEST(Config, NinePresetsMatchTheReportsColumns) {
  ASSERT_EQ(PresetNames().size(), 9u);
  for (const std::string& name : PresetNames()) {
    absl::StatusOr<Config> c = Preset(name);
    ASSERT_TRUE(c.ok()) << name;
    EXPECT_TRUE(c->Validate().ok()) << name;
    EXPECT_FALSE(c->seed_compatible) << name;
  }
  EXPECT_EQ(Preset("median-16-2")->max_depth, 16);
  EXPECT_EQ(Preset("median-16-2")->max_leaf_size, 2);
  EXPECT_FALSE(Preset("median-24-8")->use_binning);
  EXPECT_EQ(Preset("median-24-8")->max_leaf_size, 8);
  EXPECT_TRUE(Preset("binning-8-driving")->use_driving_axis);
  EXPECT_FALSE(Preset("binning-8")->use_driving_axis);
  EXPECT_EQ(Preset("binning-32")->bins, 32);
  for (const char* name : {"clipping", "pruning", "clipping-pruning"}) {
    const Config c = *Preset(name);
    EXPECT_EQ(c.max_depth, 24);
    EXPECT_EQ(c.max_leaf_size, 8);
    EXPECT_TRUE(c.use_binning && c.use_driving_axis);
    EXPECT_EQ(c.bins, 8);
  }
  EXPECT_TRUE(Preset("clipping")->use_clipping);
  EXPECT_FALSE(Preset("clipping")->use_pruning);
  EXPECT_TRUE(Preset("pruning")->use_pruning);
  EXPECT_FALSE(Preset("pruning")->use_clipping);
  EXPECT_TRUE(Preset("clipping-pruning")->use_clipping && Preset("clipping-pruning")->use_pruning);
  // As the report's numbers show it was run: on the Binning 32 (all axes) tree.
  const Config seed = *Preset("pruning-seed");
  EXPECT_EQ(seed.bins, 32);
  EXPECT_FALSE(seed.use_driving_axis);
  EXPECT_TRUE(seed.seed_compatible);
}

TEST(Config, UnknownPresetIsNotFound) {
  absl::StatusOr<Config> c = Preset("binning-9");
  EXPECT_EQ(c.status().code(), absl::StatusCode::kNotFound);
  EXPECT_NE(c.status().message().find("binning-9"), std::string::npos);
}

TEST(Config, EveryKnownPresetIsAcceptedAndNamedInTheError) {
  const std::vector<std::string> known = KnownPresetNames();
  EXPECT_EQ(known.size(), PresetNames().size() + 1 + ExtraPresetNames().size());
  for (const std::string& name : known) EXPECT_TRUE(Preset(name).ok()) << name;
  const absl::StatusOr<Config> bad = Preset("sah-nonsense");
  ASSERT_FALSE(bad.ok());
  for (const std::string& name : known) {
    EXPECT_NE(bad.status().message().find(name), std::string::npos) << name;
  }
}

TEST(Config, ValidateRejectsOutOfRangeValues) {
  Config c;
  c.max_depth = 61;
  EXPECT_FALSE(c.Validate().ok());
  c = Config();
  c.bins = 1;
  EXPECT_FALSE(c.Validate().ok());
  c = Config();
  c.max_leaf_size = -1;
  EXPECT_FALSE(c.Validate().ok());
  c = Config();
  c.sah_packet = 0;
  EXPECT_FALSE(c.Validate().ok());
  c.sah_packet = 65;
  EXPECT_FALSE(c.Validate().ok());
  c.sah_packet = 4;
  EXPECT_TRUE(c.Validate().ok());
}

}  // namespace
}  // namespace kdtree
