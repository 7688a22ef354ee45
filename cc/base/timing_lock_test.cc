#include "cc/base/timing_lock.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <memory>
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

// A timed step waits while another process does untimed work under the
// shared hold; untimed work of two processes does not wait for each other.
TEST(TimingLock, TimedStepsWaitForSharedHolders) {
  auto untimed = std::make_unique<TimingLock>(LockPath());
  ASSERT_TRUE(untimed->HoldShared().ok());
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    TimingLock other(LockPath());
    if (!other.HoldShared().ok()) _exit(2);  // shared beside shared: at once
    const double shared_wait = other.waited_seconds();
    if (!other.Acquire().ok()) _exit(1);  // timed: waits for the parent
    _exit(shared_wait < 0.2 ? 0 : 3);
  }
  usleep(300 * 1000);
  untimed->Release();  // not timing: still shared
  usleep(100 * 1000);
  int status = 0;
  EXPECT_EQ(waitpid(child, &status, WNOHANG), 0) << "the timed step ran beside shared work";
  untimed.reset();  // the process's work is done: unlocked
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << WEXITSTATUS(status);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(s, 0.35);
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
