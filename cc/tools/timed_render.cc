#include "cc/tools/timed_render.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cc/base/median.h"

namespace kdtree {

bool MoreRuns(const std::vector<double>& runs, int repeats, double budget_s) {
  if (runs.empty()) return true;
  if (static_cast<int>(runs.size()) >= repeats) return false;
  double spent = 0;
  for (double r : runs) spent += r;
  return budget_s <= 0 || spent < budget_s;
}

absl::Status TimeRounds(const TriangleSoup& soup, const View& view, int repeats, double budget_s,
                        std::vector<Lane>* lanes, const StepFn& step) {
  std::vector<double> rounds;
  for (int i = 0; MoreRuns(rounds, repeats, budget_s); ++i) {
    double round_s = 0;
    for (Lane& lane : *lanes) {
      if (step) step(absl::StrFormat("round %d/%d: %s", i + 1, repeats, lane.name));
      if (lane.replay != nullptr) lane.replay->Rewind();
      RenderResult r = Render(soup, *lane.tracer, view, lane.opt);
      if (lane.replay != nullptr && lane.replay->overran()) {
        return absl::InternalError(absl::StrCat(lane.name, ": the render ran past its recorded answers"));
      }
      const bool first = lane.last.rgb.empty();
      if (!first && (r.rgb != lane.last.rgb || r.p_hit != lane.last.p_hit || r.s_hit != lane.last.s_hit)) {
        return absl::InternalError(absl::StrCat(lane.name, ": a timed render differs from the one it must reproduce"));
      }
      lane.timed.t_r.push_back(r.seconds);
      lane.timed.t_primary.push_back(r.primary.seconds);
      lane.timed.t_shadow.push_back(r.shadow.seconds);
      lane.timed.t_ao.push_back(r.ao.seconds);
      round_s += r.seconds;
      lane.last = std::move(r);
    }
    rounds.push_back(round_s);
  }
  return absl::OkStatus();
}

nlohmann::ordered_json EffectJson(uint64_t rays, const std::vector<double>& runs) {
  return {{"rays", rays}, {"seconds", Median(runs)}, {"seconds_runs", runs}};
}

nlohmann::ordered_json EffectsJson(const Lane& lane) {
  const RenderResult& r = lane.last;
  return {{"primary", EffectJson(r.primary.rays, lane.timed.t_primary)},
          {"shadow", EffectJson(r.shadow.rays, lane.timed.t_shadow)},
          {"ao", EffectJson(r.ao.rays, lane.timed.t_ao)}};
}

}  // namespace kdtree
