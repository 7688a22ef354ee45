#include "cc/base/timing_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace kdtree {

std::string TimingLock::DefaultPath() {
  const char* env = std::getenv("KDTREE_TIMING_LOCK");
  return env != nullptr ? env : "/tmp/kdtree-timing.lock";
}

absl::Status TimingLock::Open() {
  if (fd_ >= 0) return absl::OkStatus();
  fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ >= 0) return absl::OkStatus();
  return absl::FailedPreconditionError(
      absl::StrCat(path_, ": cannot open the timing lock: ", std::strerror(errno),
                   " (set KDTREE_TIMING_LOCK to another file, or to 'off' to time without it)"));
}

absl::Status TimingLock::Lock(int op) {
  if (absl::Status st = Open(); !st.ok()) return st;
  const auto start = std::chrono::steady_clock::now();
  int rc;
  do {
    rc = flock(fd_, op);  // converts a lock already held (not atomically)
  } while (rc != 0 && errno == EINTR);
  if (rc != 0) return absl::InternalError(absl::StrCat(path_, ": cannot lock: ", std::strerror(errno)));
  waited_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return absl::OkStatus();
}

absl::Status TimingLock::Acquire() {
  if (!enabled() || held_) return absl::OkStatus();
  if (absl::Status st = Lock(LOCK_EX); !st.ok()) return st;
  held_ = true;
  return absl::OkStatus();
}

absl::Status TimingLock::HoldShared() {
  if (!enabled()) return absl::OkStatus();
  shared_ = true;
  return held_ ? absl::OkStatus() : Lock(LOCK_SH);
}

void TimingLock::Release() {
  if (!held_) return;
  held_ = false;
  if (!shared_ || !Lock(LOCK_SH).ok()) Unlock();
}

void TimingLock::Unlock() {
  if (fd_ >= 0) {
    flock(fd_, LOCK_UN);
    close(fd_);
  }
  fd_ = -1;
  held_ = false;
}

}  // namespace kdtree
