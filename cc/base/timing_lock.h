// A machine-wide lock around timed steps, so that no two timed steps of this
// project (kdrt's timed rounds, the benches' rounds) ever run at the same time
// on one machine, whoever started them: a second process waits at Acquire()
// until the first releases. Untimed work (loading, counting passes, checks
// against brute force or Embree) runs outside it and may overlap. An advisory
// flock(2) on a file: the kernel drops it when a process dies.
#ifndef KDTREE_CC_BASE_TIMING_LOCK_H_
#define KDTREE_CC_BASE_TIMING_LOCK_H_

#include <string>

#include "absl/status/status.h"

namespace kdtree {

class TimingLock {
 public:
  // $KDTREE_TIMING_LOCK, else /tmp/kdtree-timing.lock; "off" (or "") = no lock.
  static std::string DefaultPath();

  explicit TimingLock(std::string path = DefaultPath()) : path_(std::move(path)) {}
  ~TimingLock() { Release(); }
  TimingLock(const TimingLock&) = delete;
  TimingLock& operator=(const TimingLock&) = delete;

  // Blocks until this process holds the lock (at once when disabled). Error:
  // the lock file cannot be opened or locked (message names it).
  absl::Status Acquire();
  void Release();

  bool enabled() const { return !path_.empty() && path_ != "off"; }
  // The lock file, or "" when disabled: what records show as timing_lock.
  std::string path() const { return enabled() ? path_ : ""; }
  // Seconds spent waiting in Acquire() so far.
  double waited_seconds() const { return waited_s_; }

 private:
  std::string path_;
  int fd_ = -1;
  bool held_ = false;
  double waited_s_ = 0;
};

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_TIMING_LOCK_H_
