#include "cc/tools/timed_render.h"

#include "absl/strings/str_format.h"
#include "cc/render/json.h"

namespace kdtree {

bool MoreRuns(const std::vector<double>& runs, int repeats, double budget_s) {
  if (runs.empty()) return true;
  if (static_cast<int>(runs.size()) >= repeats) return false;
  double spent = 0;
  for (double r : runs) spent += r;
  return budget_s <= 0 || spent < budget_s;
}

Timed TimeRenders(const TriangleSoup& soup, const Tracer& tracer, const View& view,
                  const RenderOptions& opt, int repeats, double budget_s,
                  const std::function<void(const std::string&)>& step) {
  Timed t;
  for (int i = 0; MoreRuns(t.t_r, repeats, budget_s); ++i) {
    if (step) step(absl::StrFormat("%s render %d/%d", tracer.name(), i + 1, repeats));
    t.last = Render(soup, tracer, view, opt);
    t.t_r.push_back(t.last.seconds);
    t.t_primary.push_back(t.last.primary.seconds);
    t.t_shadow.push_back(t.last.shadow.seconds);
    t.t_ao.push_back(t.last.ao.seconds);
  }
  return t;
}

std::string EffectJson(const char* name, uint64_t rays, const std::vector<double>& runs) {
  return absl::StrFormat("%s: {\"rays\": %d, \"seconds\": %s, \"seconds_runs\": %s}",
                         JsonQuote(name), rays, JsonNumber(Median(runs)), JsonNumberArray(runs));
}

}  // namespace kdtree
