// Single-thread timed rounds on the quieter of the machine's CPUs.
//
// On this project's 2-vCPU virtual machines one vCPU is at times markedly
// slower than the other (load on the host behind it): the same render_bench
// process pinned to it rendered 1.4 times slower, the renderer's own camera
// pass (the replay) 1.7 times (2026-12-06). A process the scheduler puts on
// that vCPU times everything there, and the slowdown is not the same for
// every tracer: in the standard sweep at 9b4d925, pooled over three
// processes, the processes whose replay ran slow gave the kd-tree 0.025
// lower single-ray ratios to Embree on average (up to 0.07), the best-mode
// ratios 0.037 lower (the replay ran 1.7 times slower in them, the pinned
// process's signature); the other processes agreed to 0.02. Both
// tracers of a round run on one CPU either way; choosing the quieter one
// takes the host's load out of the comparison while one CPU is quiet (at
// other times both were slow; the probes, which the records keep, show it).
//
// ScopedQuietCpu probes each CPU the calling thread may run on
// (sched_getaffinity) with one fixed workload (a dependent walk over 1 MiB
// with a division per step, about 3 ms; the fastest of five runs), pins the
// calling thread to the fastest CPU (sched_setaffinity), and restores the
// thread's CPU set when it goes out of scope. Only for single-thread timed
// work: a render or build with more threads needs every CPU.
#ifndef KDTREE_CC_BASE_QUIET_CPU_H_
#define KDTREE_CC_BASE_QUIET_CPU_H_

#include <vector>

#include "nlohmann/json.hpp"

namespace kdtree {

struct CpuProbe {
  int cpu = -1;
  double ms = 0;  // the fastest of the probe's runs on this CPU
};

// Probes every CPU the calling thread may run on, in CPU order; leaves the
// thread's CPU set as it was. Empty when the set cannot be read.
std::vector<CpuProbe> ProbeCpus();

// The fastest of `probes` (the first on a tie); -1 when empty.
int QuietestCpu(const std::vector<CpuProbe>& probes);

class ScopedQuietCpu {
 public:
  ScopedQuietCpu();  // probes, then pins the calling thread (see above)
  ~ScopedQuietCpu();
  ScopedQuietCpu(const ScopedQuietCpu&) = delete;
  ScopedQuietCpu& operator=(const ScopedQuietCpu&) = delete;

  // The CPU pinned to, or -1 when pinning failed (the thread then runs
  // wherever the scheduler puts it, as without this class).
  int cpu() const { return cpu_; }
  const std::vector<CpuProbe>& probes() const { return probes_; }

 private:
  std::vector<CpuProbe> probes_;
  int cpu_ = -1;
  bool restore_ = false;
  std::vector<unsigned char> saved_;  // the thread's cpu_set_t before
};

// What a record keeps of it (kdrt's and render_bench's "timing"): {"cpu": the
// CPU pinned to (-1: pinning failed), "cpu_probe_ms": {CPU number: probe}},
// each null without `quiet` (timing with more threads) or without probes.
nlohmann::ordered_json QuietCpuJson(const ScopedQuietCpu* quiet);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_QUIET_CPU_H_
