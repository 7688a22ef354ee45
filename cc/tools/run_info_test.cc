#include "cc/tools/run_info.h"

#include <cstdlib>

#include "cc/render/json.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(RunInfo, IsValidJsonAndKnowsTheCompileMode) {
  setenv("KDTREE_GIT_COMMIT", "0123abcd", 1);
  const RunInfo info = CollectRunInfo(".");
  EXPECT_EQ(info.git_commit, "0123abcd");
  EXPECT_TRUE(info.compilation_mode == "opt" || info.compilation_mode == "fastbuild" ||
              info.compilation_mode == "dbg")
      << info.compilation_mode;
  EXPECT_EQ(info.timestamp_utc.size(), 20u);
  absl::StatusOr<JsonValue> v = ParseJson("{" + info.ToJson() + "}", "run_info");
  ASSERT_TRUE(v.ok()) << v.status() << "\n" << info.ToJson();
  ASSERT_NE(v->Find("build"), nullptr);
  EXPECT_NE(v->Find("build")->Find("optimized"), nullptr);
  EXPECT_EQ(v->Find("git_commit")->string(), "0123abcd");
}

TEST(RunInfo, GitFailureIsTolerated) {
  unsetenv("KDTREE_GIT_COMMIT");
  const RunInfo info = CollectRunInfo("/nonexistent/repo");
  EXPECT_EQ(info.git_commit, "");
  EXPECT_TRUE(ParseJson("{" + info.ToJson() + "}", "x").ok());
}

}  // namespace
}  // namespace kdtree
