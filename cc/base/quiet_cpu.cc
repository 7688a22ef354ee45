#include "cc/base/quiet_cpu.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace kdtree {
namespace {

constexpr int kProbeRuns = 5;
constexpr int kProbeSteps = 400000;
constexpr size_t kProbeWords = size_t{1} << 18;  // 1 MiB of uint32_t

// One cycle through every word in a fixed random order (seeded): each step
// waits for the load before it, and a division per step.
std::vector<uint32_t> ProbeCycle() {
  std::vector<uint32_t> order(kProbeWords);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin() + 1, order.end(), std::mt19937(1));
  std::vector<uint32_t> next(kProbeWords);
  for (size_t k = 0; k < kProbeWords; ++k) next[order[k]] = order[(k + 1) % kProbeWords];
  return next;
}

volatile double probe_sink;

double ProbeMs(const std::vector<uint32_t>& next) {
  double best = 1e300;
  for (int r = 0; r < kProbeRuns; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    uint32_t i = 0;
    double acc = 0;
    for (int k = 0; k < kProbeSteps; ++k) {
      i = next[i];
      acc += 1.0 / (1.0 + i);
    }
    const auto t1 = std::chrono::steady_clock::now();
    probe_sink = acc + i;  // keeps the loop
    best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return best;
}

bool PinTo(int cpu) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  return sched_setaffinity(0, sizeof(one), &one) == 0;
}

}  // namespace

std::vector<CpuProbe> ProbeCpus() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) return {};
  const std::vector<uint32_t> next = ProbeCycle();
  std::vector<CpuProbe> out;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed) || !PinTo(cpu)) continue;
    out.push_back(CpuProbe{cpu, ProbeMs(next)});
  }
  sched_setaffinity(0, sizeof(allowed), &allowed);
  return out;
}

int QuietestCpu(const std::vector<CpuProbe>& probes) {
  const auto it = std::min_element(probes.begin(), probes.end(),
                                   [](const CpuProbe& a, const CpuProbe& b) { return a.ms < b.ms; });
  return it == probes.end() ? -1 : it->cpu;
}

ScopedQuietCpu::ScopedQuietCpu() {
  cpu_set_t before;
  CPU_ZERO(&before);
  if (sched_getaffinity(0, sizeof(before), &before) != 0) return;
  saved_.assign(reinterpret_cast<const unsigned char*>(&before),
                reinterpret_cast<const unsigned char*>(&before) + sizeof(before));
  probes_ = ProbeCpus();
  const int cpu = QuietestCpu(probes_);
  if (cpu >= 0 && PinTo(cpu)) {
    cpu_ = cpu;
    restore_ = true;
  }
}

ScopedQuietCpu::~ScopedQuietCpu() {
  if (!restore_) return;
  cpu_set_t before;
  std::memcpy(&before, saved_.data(), sizeof(before));
  sched_setaffinity(0, sizeof(before), &before);
}

nlohmann::ordered_json QuietCpuJson(const ScopedQuietCpu* quiet) {
  nlohmann::ordered_json out = {{"cpu", nullptr}, {"cpu_probe_ms", nullptr}};
  if (quiet == nullptr) return out;
  out["cpu"] = quiet->cpu();
  for (const CpuProbe& p : quiet->probes()) out["cpu_probe_ms"][std::to_string(p.cpu)] = p.ms;
  return out;
}

}  // namespace kdtree
