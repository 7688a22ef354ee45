#include "cc/bench/render_times.h"

#include <algorithm>

#include "cc/base/median.h"

namespace kdtree {
namespace bench {

namespace {
double MinOf(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
}  // namespace

double PairedRatio(const std::vector<double>& a, const std::vector<double>& b) {
  return Median(PairedRatios(a, b));
}

Json TracerTimes(const std::vector<Entry>& entries) {
  Json tracers = Json::object();
  for (const Entry& e : entries) {
    tracers[e.name] = {{"T_R_runs", e.runs},
                       {"T_R_median", Median(e.runs)},
                       {"T_R_min", MinOf(e.runs)},
                       {"mrays_per_s_median", e.rays / Median(e.runs) / 1e6},
                       {"primary_s_median", Median(e.primary)},
                       {"secondary_s_median", Median(e.secondary)},
                       {"primary_s_runs", e.primary},
                       {"secondary_s_runs", e.secondary},
                       {"first_over_this_paired", PairedRatio(entries[0].runs, e.runs)},
                       {"T_R_warmup_runs", e.warmup}};
  }
  return tracers;
}

Json RatiosTo(const std::vector<Entry>& entries, size_t n_kd, const Entry& embree) {
  Json ratios = Json::object();
  for (size_t k = 0; k < n_kd; ++k) {
    const Entry& e = entries[k];
    ratios[e.name] = {{"median", Median(embree.runs) / Median(e.runs)},
                      {"min", MinOf(embree.runs) / MinOf(e.runs)},
                      {"paired", PairedRatio(embree.runs, e.runs)}};
  }
  return ratios;
}

Json TraceOnly(const std::vector<Entry>& entries, size_t n_kd, size_t n_traced, Json* tracers) {
  std::vector<std::vector<double>> trace(n_traced);
  for (size_t k = 0; k < n_traced; ++k) {
    const Entry& e = entries[k];
    const Entry& replay = entries[n_traced + (e.packets ? 1 : 0)];
    trace[k] = LessPerRound(e.runs, replay.runs);
    (*tracers)[e.name]["trace_s_median"] = Median(trace[k]);
  }
  Json out = Json::object();
  for (size_t k = 0; k < n_kd; ++k) {
    Json r = Json::object();
    for (size_t m = n_kd; m < n_traced; ++m) r[entries[m].name] = PairedRatio(trace[m], trace[k]);
    out[entries[k].name] = std::move(r);
  }
  return out;
}

}  // namespace bench
}  // namespace kdtree
