#include "cc/kdtree/env_file.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

TEST(EnvFile, ParsesTheReportsSnippet) {
  const std::string text = R"(RTCore {
    castShadowRays ON
}

KDTree {
    maxDepth 24
    maxLeafSize 4
    Binning {
        useBinning ON
        useDrivingAxis ON
        bins 16
    }
    useClipping ON
    usePruning ON
}
)";
  Config base;
  base.max_depth = 3;
  base.bins = 5;
  base.use_clipping = false;
  absl::StatusOr<EnvResult> r = ParseEnvironment(text, "report.env", base);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->config, Config());
}

TEST(EnvFile, RoundTripsEveryPreset) {
  for (const std::string& name : AllPresetNames()) {
    const Config c = *Preset(name);
    absl::StatusOr<EnvResult> r = ParseEnvironment(c.ToEnvironment(), name + ".env");
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_EQ(r->config, c) << name;
  }
}

TEST(EnvFile, SahConstantsRoundTripAndAreChecked) {
  Config c = *Preset("sah-packet");
  c.traversal_cost = 7.25;
  c.intersection_cost = 0.1;  // not exact in binary: printed with 17 digits
  c.empty_bonus = 0.9;
  absl::StatusOr<EnvResult> r = ParseEnvironment(c.ToEnvironment(), "k.env");
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->config, c);
  EXPECT_NE(c.ToEnvironment().find("traversalCost 7.25"), std::string::npos);
  EXPECT_EQ(Config().ToEnvironment().find("traversalCost"), std::string::npos);  // defaults unprinted
  absl::StatusOr<EnvResult> bad =
      ParseEnvironment("KDTree {\n  traversalCost fast\n}\n", "bad.env");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("bad.env:2"), std::string::npos) << bad.status();
}

TEST(EnvFile, OneLineFormCommentsAndOtherBlocks) {
  absl::StatusOr<EnvResult> r = ParseEnvironment(
      "# nanoGOLEM\nCamera { width 800 Sub { a b } }\n"
      "KDTree { maxDepth 16 maxLeafSize 2 Binning { useBinning OFF } useClipping off "
      "usePruning false } // end\n",
      "x.env");
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->config.max_depth, 16);
  EXPECT_EQ(r->config.max_leaf_size, 2);
  EXPECT_FALSE(r->config.use_binning);
  EXPECT_FALSE(r->config.use_clipping);
  EXPECT_FALSE(r->config.use_pruning);
  ASSERT_EQ(r->skipped_blocks.size(), 1u);
  EXPECT_EQ(r->skipped_blocks[0], "Camera");
}

struct BadCase {
  const char* text;
  const char* where;   // expected "file:line"
  const char* reason;  // expected part of the message
};

TEST(EnvFile, ErrorsNameFileLineAndReason) {
  const BadCase cases[] = {
      {"KDTree {\n maxDepth abc\n}", "bad.env:2", "expected an integer, got 'abc'"},
      {"KDTree {\n useClipping MAYBE\n}", "bad.env:2", "expected ON or OFF"},
      {"KDTree {\n\n maxDepht 3\n}", "bad.env:3", "unknown option 'maxDepht'"},
      {"KDTree {\n maxDepth 3\n", "bad.env:1", "not closed"},
      {"KDTree maxDepth 3", "bad.env:1", "expected '{'"},
      {"}", "bad.env:1", "unexpected '}'"},
      {"KDTree {\n maxDepth }", "bad.env:2", "has no value"},
      {"KDTree { maxDepth 99 }", "bad.env", "maxDepth must be in [0, 60]"},
      {"KDTree { Binning { bins 1 } }", "bad.env", "bins must be in"},
      {"RTCore { castShadowRays }", "bad.env:1", "has no value"},
      {"Other { {", "bad.env:1", "not closed"},
  };
  for (const BadCase& c : cases) {
    absl::StatusOr<EnvResult> r = ParseEnvironment(c.text, "bad.env");
    ASSERT_FALSE(r.ok()) << c.text;
    const std::string msg(r.status().message());
    EXPECT_NE(msg.find(c.where), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.reason), std::string::npos) << msg;
  }
}

// The matrix's variants (experiments/matrix.json, the one list): the
// report's nine ("variants") and those beyond it ("beyond_variants").
std::vector<std::string> MatrixVariants(const char* key) {
  std::ifstream in("experiments/matrix.json");
  EXPECT_TRUE(in.good()) << "experiments/matrix.json not in the runfiles";
  const nlohmann::json matrix = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  EXPECT_TRUE(matrix.is_object() && matrix.contains(key) && matrix[key].is_array()) << key;
  return matrix.is_object() && matrix.contains(key) ? matrix[key].get<std::vector<std::string>>()
                                                    : std::vector<std::string>();
}

// Issue 24: a directory given as the environment file is refused by name
// (it was read as an empty file: the preset alone, exit 0).
TEST(EnvFile, ADirectoryIsRefusedByName) {
  const char* dir = std::getenv("TEST_TMPDIR");
  ASSERT_NE(dir, nullptr);
  absl::StatusOr<EnvResult> r = LoadEnvironmentFile(dir);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), std::string(dir) + ": the environment file is a directory");
}

TEST(EnvFile, TheMatrixsNineAreTheReportsPresets) {
  EXPECT_EQ(MatrixVariants("variants"), PresetNames());
}

TEST(EnvFile, ExperimentPresetFilesEqualTheNamedPresets) {
  std::vector<std::string> names = MatrixVariants("variants");
  const std::vector<std::string> beyond = MatrixVariants("beyond_variants");
  names.insert(names.end(), beyond.begin(), beyond.end());
  ASSERT_GE(names.size(), 9u);
  for (const std::string& name : names) {
    absl::StatusOr<EnvResult> r = LoadEnvironmentFile("experiments/presets/" + name + ".env");
    ASSERT_TRUE(r.ok()) << r.status();
    absl::StatusOr<Config> preset = Preset(name);
    ASSERT_TRUE(preset.ok()) << preset.status();
    EXPECT_EQ(r->config, *preset) << name;
  }
}

TEST(EnvFile, MissingFileIsNamed) {
  absl::StatusOr<EnvResult> r = LoadEnvironmentFile("/nonexistent/k.env");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("/nonexistent/k.env"), std::string::npos);
}

}  // namespace
}  // namespace kdtree
