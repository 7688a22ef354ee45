#include "cc/base/timing_lock.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string LockPath() { return ::testing::TempDir() + "/timing.lock"; }

TEST(TimingLock, SecondProcessWaitsForTheFirst) {
  TimingLock first(LockPath());
  ASSERT_TRUE(first.Acquire().ok());
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    TimingLock second(LockPath());
    _exit(second.Acquire().ok() ? 0 : 1);
  }
  usleep(300 * 1000);
  first.Release();
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(s, 0.25) << "the child did not wait for the lock";
}

TEST(TimingLock, ReacquiredAfterRelease) {
  TimingLock lock(LockPath());
  ASSERT_TRUE(lock.Acquire().ok());
  lock.Release();
  ASSERT_TRUE(lock.Acquire().ok());
  EXPECT_EQ(lock.path(), LockPath());
}

TEST(TimingLock, OffMeansNoLock) {
  TimingLock lock("off");
  EXPECT_FALSE(lock.enabled());
  EXPECT_TRUE(lock.Acquire().ok());
  EXPECT_EQ(lock.path(), "");
}

TEST(TimingLock, UnopenableFileIsNamed) {
  TimingLock lock("/nonexistent-dir/x.lock");
  const absl::Status st = lock.Acquire();
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("/nonexistent-dir/x.lock"), std::string::npos) << st;
}

}  // namespace
}  // namespace kdtree
