#include "cc/base/provenance.h"

#include <limits.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Provenance, KnowsTheCompileModeAndHonoursOverrides) {
  setenv("KDTREE_GIT_COMMIT", "0123abcd", 1);
  setenv("KDTREE_SOURCE_TREE", "feedbeef", 1);
  const Provenance p = CollectProvenance(".");
  EXPECT_EQ(p.commit, "0123abcd");
  EXPECT_EQ(p.source_tree, "feedbeef");
  EXPECT_TRUE(p.compilation_mode == "opt" || p.compilation_mode == "fastbuild" || p.compilation_mode == "dbg")
      << p.compilation_mode;
  EXPECT_GE(p.cores, 1);
  EXPECT_EQ(p.timestamp_utc.size(), 20u);
  const nlohmann::ordered_json j = p.ToJson();
  EXPECT_EQ(j["commit"], "0123abcd");
  EXPECT_EQ(j["source_tree"], "feedbeef");
  EXPECT_TRUE(j["timed_beside"].is_null()) << "no lock held: unknown";
  EXPECT_EQ(j["timing_build"], p.compilation_mode == "opt" && p.optimized && p.ndebug);
  unsetenv("KDTREE_GIT_COMMIT");
  unsetenv("KDTREE_SOURCE_TREE");
}

// A file under TEST_TMPDIR with `text`; its path.
std::string TempFile(const std::string& name, const std::string& text) {
  const std::string path = std::string(std::getenv("TEST_TMPDIR")) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Provenance, TheCpuIsNamedByFamilyModelAndStepping) {
  const std::string cpuinfo = TempFile(
      "cpuinfo",
      "processor\t: 0\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 106\n"
      "model name\t: Intel(R) Xeon(R) Processor @ 2.80GHz\nstepping\t: 6\n\n"
      "processor\t: 1\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 143\n");
  EXPECT_EQ(CpuIdentity(cpuinfo), "GenuineIntel family 6 model 106 stepping 6");
  // "model name" first: "model" must match the key exactly, not a prefix.
  EXPECT_EQ(CpuIdentity(TempFile("name_first", "model name\t: X @ 1GHz\ncpu family\t: 25\n"
                                               "model\t\t: 17\n")),
            "family 25 model 17");
  EXPECT_EQ(CpuIdentity(TempFile("no_model", "vendor_id\t: GenuineIntel\n")), "");
  EXPECT_EQ(CpuIdentity("/nonexistent/cpuinfo"), "");
}

TEST(Provenance, TheCachesAreListedByLevelAndType) {
  const std::string root = std::string(std::getenv("TEST_TMPDIR")) + "/cache";
  const char* rows[][3] = {{"1", "Data", "48K"}, {"1", "Instruction", "32K"},
                           {"2", "Unified", "1280K"}, {"3", "Unified", "49152K"}};
  for (int i = 0; i < 4; ++i) {
    const std::string dir = root + "/index" + std::to_string(i);
    ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
    std::ofstream(dir + "/level") << rows[i][0] << "\n";
    std::ofstream(dir + "/type") << rows[i][1] << "\n";
    std::ofstream(dir + "/size") << rows[i][2] << "\n";
  }
  EXPECT_EQ(CpuCaches(root), "L1d 48K, L1i 32K, L2 1280K, L3 49152K");
  // A cache without a type file is named by its level alone; a gap ends the list.
  const std::string odd = std::string(std::getenv("TEST_TMPDIR")) + "/odd_cache";
  ASSERT_EQ(std::system(("mkdir -p " + odd + "/index0 " + odd + "/index2").c_str()), 0);
  std::ofstream(odd + "/index0/level") << "2\n";
  std::ofstream(odd + "/index0/size") << "1024K\n";
  std::ofstream(odd + "/index2/level") << "3\n";
  std::ofstream(odd + "/index2/size") << "8192K\n";
  EXPECT_EQ(CpuCaches(odd), "L2 1024K");
  EXPECT_EQ(CpuCaches("/nonexistent/cache"), "");
}

TEST(Provenance, RecordsTheCpusIdentity) {
  const nlohmann::ordered_json j = CollectProvenance(".").ToJson();
  EXPECT_TRUE(j.contains("cpu_id"));
  EXPECT_TRUE(j.contains("cpu_caches"));
}

TEST(Provenance, APinnedIdentityIsTheRecordsCode) {
  setenv("KDTREE_SOURCE_ID", "c0ffee true 5eed", 1);
  const Provenance p = CollectProvenance("/nonexistent/repo");  // the script is not run
  EXPECT_EQ(p.commit, "c0ffee");
  EXPECT_TRUE(p.dirty);
  EXPECT_EQ(p.source_tree, "5eed");
  unsetenv("KDTREE_SOURCE_ID");
}

TEST(Provenance, OutsideACheckoutTheCodeIsUnknown) {
  Provenance p = CollectProvenance("/nonexistent/repo");
  EXPECT_EQ(p.commit, "");
  EXPECT_EQ(p.source_tree, "");
  nlohmann::ordered_json j = p.ToJson();
  EXPECT_TRUE(j["commit"].is_null());
  EXPECT_TRUE(j["source_tree"].is_null());
  p.timing_lock = "/tmp/x.lock";
  EXPECT_EQ(p.ToJson()["timed_beside"], 0);
}

// A checkout whose source_id.sh names commit "abc", tree "def".
std::string FakeCheckout(const std::string& name) {
  const std::string root = std::string(std::getenv("TEST_TMPDIR")) + "/" + name;
  EXPECT_EQ(std::system(("mkdir -p " + root + "/cc/base && printf 'echo abc false def\\n' > " + root +
                         "/cc/base/source_id.sh")
                            .c_str()),
            0);
  return root;
}

TEST(Provenance, ABinaryBuiltElsewhereDoesNotTakeTheCheckoutsCode) {
  const std::string root = FakeCheckout("foreign");  // no bazel-out at all
  const Provenance p = CollectProvenance(root);
  EXPECT_EQ(p.commit, "");
  EXPECT_EQ(p.source_tree, "");
}

TEST(Provenance, ABinaryBuiltInTheCheckoutTakesItsCode) {
  const std::string root = FakeCheckout("home");
  char exe[PATH_MAX];
  ASSERT_NE(realpath("/proc/self/exe", exe), nullptr);
  const std::string dir = std::string(exe).substr(0, std::string(exe).rfind('/'));
  ASSERT_EQ(symlink(dir.c_str(), (root + "/bazel-out").c_str()), 0);
  const Provenance p = CollectProvenance(root);
  EXPECT_EQ(p.commit, "abc");
  EXPECT_EQ(p.source_tree, "def");
}

}  // namespace
}  // namespace kdtree
