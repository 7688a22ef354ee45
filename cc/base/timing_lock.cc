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

absl::Status TimingLock::Acquire() {
  if (!enabled() || held_) return absl::OkStatus();
  if (fd_ < 0) {
    fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) {
      return absl::FailedPreconditionError(
          absl::StrCat(path_, ": cannot open the timing lock: ", std::strerror(errno),
                       " (set KDTREE_TIMING_LOCK to another file, or to 'off' to time without it)"));
    }
  }
  const auto start = std::chrono::steady_clock::now();
  int rc;
  do {
    rc = flock(fd_, LOCK_EX);
  } while (rc != 0 && errno == EINTR);
  if (rc != 0) return absl::InternalError(absl::StrCat(path_, ": cannot lock: ", std::strerror(errno)));
  waited_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  held_ = true;
  return absl::OkStatus();
}

void TimingLock::Release() {
  if (held_) flock(fd_, LOCK_UN);
  held_ = false;
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

}  // namespace kdtree
