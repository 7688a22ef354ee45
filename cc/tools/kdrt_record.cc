#include "cc/tools/kdrt_record.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "cc/base/fnv.h"
#include "cc/base/median.h"

namespace kdtree {

using Json = nlohmann::ordered_json;

Json TraversalJson(const TraversalCounters& c) {
  const double n = c.rays ? static_cast<double>(c.rays) : 1.0;
  return {{"rays", c.rays}, {"N_IT", c.triangle_tests / n}, {"N_TR", c.inner_visits / n},
          {"leaves", c.leaf_visits / n}};
}

void AddRenderTimes(const Lane& lane, double pixels, Json* j) {
  const double t_r = Median(lane.timed.t_r);
  (*j)["T_R"] = t_r;
  (*j)["T_R_runs"] = lane.timed.t_r;
  (*j)["T_R_warmup"] = lane.warmup_s;
  (*j)["perf_krays"] = pixels / t_r / 1000.0;
  (*j)["all_rays_per_s"] = lane.last.total_rays() / t_r;
}

Json EmbreeJson(EmbreeQuality quality, const TimedBuilds& b, const Json& disagreements, const Lane* el,
                const Lane& kl, double pixels) {
  Json e = {{"quality", EmbreeQualityName(quality)}, {"timed", el != nullptr},
            {"T_B", el ? Json(Median(b.embree_runs)) : Json()}, {"T_B_runs", b.embree_runs},
            {"T_B_warmup", b.embree_warmup}};
  if (el != nullptr) {
    AddRenderTimes(*el, pixels, &e);
    const RenderResult& er = el->last;
    for (const auto& [key, value] : {std::pair<const char*, uint64_t>{"P_hit", er.p_hit}, {"P_miss", er.p_miss},
                                     {"S_hit", er.s_hit}, {"S_miss", er.s_miss}}) {
      e[key] = value;
    }
    e["effects"] = EffectsJson(*el);
  } else {
    for (const char* k : {"T_R", "T_R_warmup", "perf_krays", "all_rays_per_s", "P_hit", "P_miss", "S_hit",
                          "S_miss", "effects"}) {
      e[k] = nullptr;
    }
    e["T_R_runs"] = Json::array();
  }
  for (const char* k : {"grazing", "at_origin", "t_guard", "other"}) {
    e[absl::StrCat("disagreements_", k)] = disagreements[k];
  }
  e["disagreements"] = disagreements["total"];
  const std::vector<double> paired = el ? PairedRatios(el->timed.t_r, kl.timed.t_r) : std::vector<double>();
  e["paired_ratio_runs"] = paired;
  e["paired_ratio"] = el ? Json(Median(paired)) : Json();
  e["perf_ratio_kd_over_embree"] = e["paired_ratio"];
  return e;
}

uint64_t Fnv64(const std::vector<uint8_t>& bytes) { return FnvBytes(bytes.data(), bytes.size()); }

}  // namespace kdtree
