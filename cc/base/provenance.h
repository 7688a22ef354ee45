// Where a record's numbers came from: the code (commit, whether the checkout
// was dirty, the id of the source tree that builds the tools), how this binary
// was compiled (optimised or not), the CPU, and whether its timed steps ran
// alone. Every result record carries it as "provenance"; the runners key
// finished jobs on it and the analysis refuses to mix provenances in a table
// (issue 22).
#ifndef KDTREE_CC_BASE_PROVENANCE_H_
#define KDTREE_CC_BASE_PROVENANCE_H_

#include <string>

#include "nlohmann/json.hpp"

namespace kdtree {

struct Provenance {
  std::string commit;       // git HEAD; "" when unknown
  bool dirty = false;       // the working tree differs from HEAD
  std::string source_tree;  // cc/base/source_id.sh's id of the tools' sources; "" when unknown
  std::string compilation_mode;  // Bazel's "opt", "fastbuild" or "dbg" ("unknown" outside Bazel)
  bool optimized = false;        // __OPTIMIZE__ (any -O level above 0)
  bool ndebug = false;           // NDEBUG (asserts off; set by -c opt)
  bool avx2 = false, avx512f = false, fma = false;  // target ISA (-march=native shows here)
  bool timing_build = false;     // opt && optimized && ndebug: its timings may be shown
  std::string compiler;          // __VERSION__
  std::string cpu_model;         // /proc/cpuinfo "model name"; "" when unknown
  // What tells two CPUs of one model name apart (a virtual machine's name,
  // "Intel(R) Xeon(R) Processor @ 2.80GHz", covers several generations):
  // CpuIdentity's family, model and stepping and CpuCaches' sizes; "" when
  // unknown.
  std::string cpu_id;
  std::string cpu_caches;
  int cores = 0;                 // CPUs this process may run on
  std::string timing_lock;       // the TimingLock its timed steps held; "" = none
  std::string timestamp_utc;     // ISO 8601, when collected

  // Work of this project's tools that ran beside this one's timed steps: 0
  // when they held the machine-wide TimingLock (timing_lock.h: timed steps
  // exclusively, other work shared), unknown (null) without it.
  nlohmann::ordered_json ToJson() const;
};

// "GenuineIntel family 6 model 106 stepping 6" from a /proc/cpuinfo (its
// first processor); "" without a family and model.
std::string CpuIdentity(const std::string& cpuinfo);

// "L1d 48K, L1i 32K, L2 1280K, L3 49152K" from a CPU's sysfs cache
// directory (/sys/devices/system/cpu/cpu0/cache); "" when unreadable.
std::string CpuCaches(const std::string& cache_dir);

// Collects it: the code identity is $KDTREE_SOURCE_ID when set (the line of
// cc/base/source_id.sh that a runner pinned when it built the tools, so a
// record names the code its binary was built from even if the checkout is
// edited while it runs), else the output of repo_root/cc/base/source_id.sh
// now when this binary was built in that checkout (it lies under
// repo_root/bazel-out); a binary from elsewhere, or a failure, leaves commit
// and source_tree empty (unknown). $KDTREE_GIT_COMMIT and
// $KDTREE_SOURCE_TREE, when set, replace the commit and the source tree
// (tests). timing_lock is left
// empty: the caller sets it when its timed steps held the lock.
Provenance CollectProvenance(const std::string& repo_root);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_PROVENANCE_H_
