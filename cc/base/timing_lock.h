// A machine-wide lock around timed steps, so that no timed step of this
// project (kdrt's timed rounds, the benches' rounds) ever runs beside other
// work of this project on one machine, whoever started it. A timed step holds
// it exclusively (Acquire()); a process's heavy untimed work (loading, warm-up
// builds, recording renders, counting passes, checks against brute force or
// Embree) holds it shared (HoldShared()): untimed work of two processes may
// overlap, but never a timed step. Measured on this 2-core VM: a second
// process's untimed work beside the timed rounds slowed the kd-tree more than
// Embree (paired kd/Embree ratios 10-35 % low), so pairing alone does not
// protect a ratio from it. An advisory flock(2) on a file: the kernel drops it
// when a process dies.
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
  ~TimingLock() { Unlock(); }
  TimingLock(const TimingLock&) = delete;
  TimingLock& operator=(const TimingLock&) = delete;

  // Blocks until this process holds the lock exclusively, for a timed step
  // (at once when disabled). Error: the lock file cannot be opened or locked
  // (message names it).
  absl::Status Acquire();
  // Ends a timed step: back to the shared hold after HoldShared(), else
  // unlocked.
  void Release();
  // From now on this process holds the lock shared whenever it is not timing
  // (call before heavy untimed work; blocks while another process times).
  absl::Status HoldShared();

  bool enabled() const { return !path_.empty() && path_ != "off"; }
  // The lock file, or "" when disabled: what records show as timing_lock.
  std::string path() const { return enabled() ? path_ : ""; }
  // Seconds spent waiting in Acquire() so far.
  double waited_seconds() const { return waited_s_; }

 private:
  absl::Status Open();
  absl::Status Lock(int op);
  void Unlock();

  std::string path_;
  int fd_ = -1;
  bool held_ = false;    // exclusively
  bool shared_ = false;  // HoldShared() was called
  double waited_s_ = 0;
};

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_TIMING_LOCK_H_
