// kdrt's progress line and the wall time of each phase of a run.
#ifndef KDTREE_CC_TOOLS_PROGRESS_H_
#define KDTREE_CC_TOOLS_PROGRESS_H_

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "nlohmann/json.hpp"

namespace kdtree {

// "\r<message>" on a terminal, nothing otherwise; and the wall seconds of
// each phase of the run (Phase: the one since the previous Phase), for the
// record: where a run's time goes.
class Progress {
 public:
  explicit Progress(std::string prefix) : prefix_(std::move(prefix)), tty_(isatty(STDERR_FILENO)) {}
  ~Progress() { Done(); }
  void Step(const std::string& what) {
    if (!tty_) return;
    std::fprintf(stderr, "\r\033[Kkdrt %s: %s", prefix_.c_str(), what.c_str());
    std::fflush(stderr);
    shown_ = true;
  }
  // Ends the phase `name` (its seconds go to phases()) and shows `next`.
  void Phase(const char* name, const std::string& next = "") {
    const auto now = std::chrono::steady_clock::now();
    phases_[name] = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    if (!next.empty()) Step(next);
  }
  const nlohmann::ordered_json& phases() const { return phases_; }
  void Done() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
    shown_ = false;
  }

 private:
  std::string prefix_;
  bool tty_, shown_ = false;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  nlohmann::ordered_json phases_;
};

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_PROGRESS_H_
