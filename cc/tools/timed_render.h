// kdrt's timing method (issue 22), the one render_bench uses too: each tracer
// first traces the frame's rays once untimed (the warm-up, recorded apart),
// then the tracers alternate in rounds, so that a slow stretch of a shared
// machine falls on all of them alike, and each ratio between two tracers is
// paired per round (the ratio of their times in one round, then the median
// over rounds). The caller holds the machine-wide TimingLock around the
// rounds.
#ifndef KDTREE_CC_TOOLS_TIMED_RENDER_H_
#define KDTREE_CC_TOOLS_TIMED_RENDER_H_

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "cc/geometry/triangle.h"
#include "cc/render/renderer.h"
#include "cc/render/replay_tracer.h"
#include "cc/render/tracer.h"
#include "cc/render/view.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// Whether to time one more round: none yet, or fewer than `repeats` so far and
// (with a budget > 0) the rounds so far took less than `budget_s` seconds in all.
bool MoreRuns(const std::vector<double>& runs, int repeats, double budget_s);

// Timed runs: every run's total, primary, shadow and AO seconds.
struct Timed {
  std::vector<double> t_r, t_primary, t_shadow, t_ao;
};

// One tracer with its render options, timed in rounds beside the others.
struct Lane {
  Lane(std::string n, const Tracer* t, const RenderOptions& o)
      : name(std::move(n)), tracer(t), opt(o) {}
  std::string name;  // for the progress line
  const Tracer* tracer = nullptr;
  RenderOptions opt;
  // A replay of recorded answers (the renderer's own work alone): rewound
  // before each timed render, which must not run past the recording.
  ReplayTracer* replay = nullptr;
  double warmup_s = 0;  // the untimed warm-up pass (set by the caller)
  RenderResult last;    // what every timed render must reproduce (image, hit
                        // counts); empty: the first timed render sets it
  Timed timed;
};

using StepFn = std::function<void(const std::string&)>;

// Timed rounds: in each, every lane renders once, in order; rounds repeat
// under MoreRuns(round totals, repeats, budget_s). Error when a render's image
// or hit counts differ from the lane's `last` (the renderer is deterministic;
// a lane may be given another tracer's result to reproduce).
absl::Status TimeRounds(const TriangleSoup& soup, const View& view, int repeats, double budget_s,
                        std::vector<Lane>* lanes, const StepFn& step);

// {"rays": n, "seconds": median, "seconds_runs": [...]}
nlohmann::ordered_json EffectJson(uint64_t rays, const std::vector<double>& runs);
// {"primary": ..., "shadow": ..., "ao": ...} of a lane.
nlohmann::ordered_json EffectsJson(const Lane& lane);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_TIMED_RENDER_H_
