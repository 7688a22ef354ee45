// render_bench's timed entries and what its records say of their times: per
// tracer, its runs and their summaries; each kd-tree variant against Embree,
// paired per round; and, with the replays (replay_tracer.h), the tracing time
// alone.
#ifndef KDTREE_CC_BENCH_RENDER_TIMES_H_
#define KDTREE_CC_BENCH_RENDER_TIMES_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cc/bench/bench_record.h"
#include "cc/bench/render_check.h"
#include "cc/render/replay_tracer.h"

namespace kdtree {
namespace bench {

// A variant and its times, one per round in round order.
struct Entry : RenderVariant {
  Entry(std::string n, const Tracer* t, bool p = false, bool s = false)
      : RenderVariant{std::move(n), t, p, s, std::string()} {}
  std::vector<double> runs, primary, secondary;  // T_R; primary; shadow + AO
  std::vector<double> warmup;                    // untimed T_R before the rounds
  uint64_t rays = 0;
  ReplayTracer* replay = nullptr;  // the renderer's own work (--replay)
};

// Median over rounds of a[r] / b[r] (whole rounds ran up to 34 % apart on
// the measured VMs; pairing puts such a stretch on both).
double PairedRatio(const std::vector<double>& a, const std::vector<double>& b);

// Per entry: its runs, their median and minimum, rays per second, the
// passes' medians, the first entry's T_R over its own (paired), warm-ups.
Json TracerTimes(const std::vector<Entry>& entries);

// Per kd-tree variant (the first n_kd entries): `embree`'s T_R over its own,
// of the medians, of the minima, and paired.
Json RatiosTo(const std::vector<Entry>& entries, size_t n_kd, const Entry& embree);

// Each tracer's render less the replay of its mode (entries[n_traced] single
// rays, entries[n_traced + 1] packets), round by round: its tracing time
// alone. Adds trace_s_median to each of the first n_traced entries' records
// in *tracers, and returns, per kd-tree (the first n_kd), the paired ratio
// of every other tracer's tracing time to its own.
Json TraceOnly(const std::vector<Entry>& entries, size_t n_kd, size_t n_traced, Json* tracers);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_RENDER_TIMES_H_
