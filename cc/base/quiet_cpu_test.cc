#include "cc/base/quiet_cpu.h"

#include <sched.h>

#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::vector<int> AllowedCpus() {
  cpu_set_t s;
  CPU_ZERO(&s);
  EXPECT_EQ(sched_getaffinity(0, sizeof(s), &s), 0);
  std::vector<int> out;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &s)) out.push_back(c);
  }
  return out;
}

// Whether this environment lets a thread set its own CPUs (a sandbox may
// not): the tests that pin are skipped where it does not.
bool CanPin() {
  cpu_set_t s;
  CPU_ZERO(&s);
  return sched_getaffinity(0, sizeof(s), &s) == 0 && sched_setaffinity(0, sizeof(s), &s) == 0;
}

TEST(QuietCpuTest, ProbesEveryAllowedCpuAndLeavesTheSetAsItWas) {
  if (!CanPin()) GTEST_SKIP() << "sched_setaffinity is not allowed here";
  const std::vector<int> before = AllowedCpus();
  const std::vector<CpuProbe> probes = ProbeCpus();
  ASSERT_EQ(probes.size(), before.size());
  for (size_t k = 0; k < probes.size(); ++k) {
    EXPECT_EQ(probes[k].cpu, before[k]);
    EXPECT_GT(probes[k].ms, 0.1);  // 400,000 dependent loads: not optimized away
  }
  EXPECT_EQ(AllowedCpus(), before);
}

TEST(QuietCpuTest, QuietestIsTheFastestProbe) {
  EXPECT_EQ(QuietestCpu({}), -1);
  EXPECT_EQ(QuietestCpu({{0, 3.7}, {1, 2.9}, {2, 3.0}}), 1);
  EXPECT_EQ(QuietestCpu({{4, 2.0}, {5, 2.0}}), 4);  // a tie: the first
}

TEST(QuietCpuTest, PinsToTheQuietestAndRestores) {
  if (!CanPin()) GTEST_SKIP() << "sched_setaffinity is not allowed here";
  const std::vector<int> before = AllowedCpus();
  {
    const ScopedQuietCpu pin;
    ASSERT_GE(pin.cpu(), 0);
    EXPECT_EQ(AllowedCpus(), std::vector<int>{pin.cpu()});
    EXPECT_EQ(pin.cpu(), QuietestCpu(pin.probes()));
    EXPECT_EQ(pin.probes().size(), before.size());
  }
  EXPECT_EQ(AllowedCpus(), before);
}

TEST(QuietCpuTest, JsonOfThePin) {
  EXPECT_EQ(QuietCpuJson(nullptr).dump(), R"({"cpu":null,"cpu_probe_ms":null})");
  if (!CanPin()) GTEST_SKIP() << "sched_setaffinity is not allowed here";
  const ScopedQuietCpu pin;
  const nlohmann::ordered_json j = QuietCpuJson(&pin);
  EXPECT_EQ(j["cpu"], pin.cpu());
  ASSERT_EQ(j["cpu_probe_ms"].size(), pin.probes().size());
  for (const CpuProbe& p : pin.probes()) EXPECT_EQ(j["cpu_probe_ms"][std::to_string(p.cpu)], p.ms);
}

TEST(QuietCpuTest, OneAllowedCpuIsTheOneChosen) {
  if (!CanPin()) GTEST_SKIP() << "sched_setaffinity is not allowed here";
  const std::vector<int> before = AllowedCpus();
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(before.back(), &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
  {
    const ScopedQuietCpu pin;
    EXPECT_EQ(pin.cpu(), before.back());
    EXPECT_EQ(pin.probes().size(), 1u);
  }
  EXPECT_EQ(AllowedCpus(), std::vector<int>{before.back()});
  cpu_set_t all;
  CPU_ZERO(&all);
  for (const int c : before) CPU_SET(c, &all);
  ASSERT_EQ(sched_setaffinity(0, sizeof(all), &all), 0);
}

}  // namespace
}  // namespace kdtree
