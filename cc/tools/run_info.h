// Where a timed run came from: compile mode and flags of this binary, the git
// commit of the sources, the CPU model and a UTC timestamp, as one JSON object
// for the result records.
#ifndef KDTREE_CC_TOOLS_RUN_INFO_H_
#define KDTREE_CC_TOOLS_RUN_INFO_H_

#include <string>

namespace kdtree {

struct RunInfo {
  std::string compilation_mode;  // Bazel's "opt", "fastbuild" or "dbg" ("unknown" outside Bazel)
  bool optimized = false;        // __OPTIMIZE__ (any -O level above 0)
  bool ndebug = false;           // NDEBUG (asserts off; set by -c opt)
  bool avx2 = false, avx512f = false, fma = false;  // target ISA (-march=native shows here)
  bool timing_build = false;     // compilation_mode == "opt" && optimized && ndebug
  std::string compiler;          // __VERSION__
  std::string git_commit;        // "" when unknown
  bool git_dirty = false;        // tracked files differ from the commit
  std::string cpu_model;         // /proc/cpuinfo "model name", "" when unknown
  std::string timestamp_utc;     // ISO 8601

  std::string ToJson() const;    // {"build": {...}, "git_commit": ..., ...} members only, no braces
};

// Git commit: $KDTREE_GIT_COMMIT when set, else `git -C repo_root rev-parse
// HEAD` (failure tolerated: empty). Dirty: `git status --porcelain
// --untracked-files=no` non-empty.
RunInfo CollectRunInfo(const std::string& repo_root);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_RUN_INFO_H_
