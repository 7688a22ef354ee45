#include "cc/tools/kdrt_config.h"

#include <cstdlib>
#include <fstream>
#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TempFile(const std::string& name, const std::string& text) {
  const char* dir = std::getenv("TEST_TMPDIR");
  const std::string path = std::string(dir ? dir : "/tmp") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(KdrtConfig, DefaultIsTheReportsFinalPreset) {
  absl::StatusOr<ResolvedConfig> r = ResolveConfig(ConfigFlags());
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->preset, "clipping-pruning");
  EXPECT_EQ(r->label, "clipping-pruning");
  EXPECT_TRUE(r->config == *Preset("clipping-pruning"));
  EXPECT_TRUE(r->overrides.empty());
}

TEST(KdrtConfig, EnvOnTopOfPresetThenFlagsOnTopOfBoth) {
  ConfigFlags f;
  f.preset = "binning-8";
  f.env = TempFile("deep.env", "KDTree { maxDepth 30 maxLeafSize 3 }\n");
  absl::StatusOr<ResolvedConfig> r = ResolveConfig(f);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->config.max_depth, 30);
  EXPECT_EQ(r->config.max_leaf_size, 3);
  EXPECT_EQ(r->config.bins, Preset("binning-8")->bins);  // kept from the preset
  EXPECT_EQ(r->label, "binning-8+deep");
  f.max_leaf_size = "6";
  f.clipping = "ON";
  f.shadows = "off";
  r = ResolveConfig(f);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->config.max_depth, 30);
  EXPECT_EQ(r->config.max_leaf_size, 6);
  EXPECT_TRUE(r->config.use_clipping);
  EXPECT_FALSE(r->config.cast_shadow_rays);
  EXPECT_EQ(r->label, "binning-8+deep+custom");
  ASSERT_EQ(r->overrides.size(), 3u);
  EXPECT_EQ(r->overrides[0], "max_leaf_size=6");
}

TEST(KdrtConfig, EnvNamedLikeThePresetKeepsThePresetLabel) {
  ConfigFlags f;
  f.preset = "pruning";
  f.env = TempFile("pruning.env", "KDTree { maxDepth 24 }\n");
  absl::StatusOr<ResolvedConfig> r = ResolveConfig(f);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->label, "pruning");
  f.label = "mine";
  EXPECT_EQ(ResolveConfig(f)->label, "mine");
}

TEST(KdrtConfig, BadFlagsAreErrors) {
  ConfigFlags f;
  f.preset = "nope";
  EXPECT_FALSE(ResolveConfig(f).ok());
  f = ConfigFlags();
  f.max_depth = "deep";
  EXPECT_FALSE(ResolveConfig(f).ok());
  f = ConfigFlags();
  f.pruning = "maybe";
  EXPECT_FALSE(ResolveConfig(f).ok());
  f = ConfigFlags();
  f.bins = "1";  // Config::Validate
  EXPECT_FALSE(ResolveConfig(f).ok());
  f = ConfigFlags();
  f.env = "/nonexistent.env";
  EXPECT_FALSE(ResolveConfig(f).ok());
}

TEST(KdrtConfig, BoolSpellings) {
  for (const char* t : {"on", "ON", "true", "1", "yes"}) EXPECT_TRUE(*ParseBoolFlag("x", t)) << t;
  for (const char* t : {"off", "False", "0", "no"}) EXPECT_FALSE(*ParseBoolFlag("x", t)) << t;
  EXPECT_FALSE(ParseBoolFlag("x", "").ok());
}

}  // namespace
}  // namespace kdtree
