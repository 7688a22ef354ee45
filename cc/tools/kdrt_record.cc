#include "cc/tools/kdrt_record.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/base/fnv.h"
#include "cc/base/median.h"
#include "cc/kdtree/ray_packet.h"

namespace kdtree {

using Json = nlohmann::ordered_json;

Json ConfigJson(const Config& c) {
  return {{"max_depth", c.max_depth},         {"max_leaf_size", c.max_leaf_size},
          {"use_binning", c.use_binning},     {"use_driving_axis", c.use_driving_axis},
          {"bins", c.bins},                   {"use_clipping", c.use_clipping},
          {"use_pruning", c.use_pruning},     {"cast_shadow_rays", c.cast_shadow_rays},
          {"seed_compatible", c.seed_compatible}};
}

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
  if (b.embree != nullptr) e["bvh_bytes"] = b.embree->bvh_bytes();
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

void AddCountsAndStats(const RayCounts& counts, const TreeStats& stats, const RenderResult& r, Json* rec) {
  (*rec)["N_IT"] = counts.n_it();
  (*rec)["N_TR"] = counts.n_tr();
  (*rec)["traversal"] = {{"primary", TraversalJson(counts.by_kind[0])},
                         {"shadow", TraversalJson(counts.by_kind[1])},
                         {"ao", TraversalJson(counts.by_kind[2])}};
  (*rec)["counting_mismatches"] = counts.result_mismatches;
  const Json tree_stats = StatsToJson(stats);  // items() refers to it: not a temporary
  for (const auto& [key, value] : tree_stats.items()) (*rec)[key] = value;
  for (const auto& [key, value] : {std::pair<const char*, uint64_t>{"P_hit", r.p_hit}, {"P_miss", r.p_miss},
                                   {"S_hit", r.s_hit}, {"S_miss", r.s_miss}, {"AO_hit", r.ao_hit},
                                   {"AO_miss", r.ao_miss}}) {
    (*rec)[key] = value;
  }
}

namespace {

const Lane* FindLane(const std::vector<Lane>& lanes, const std::string& name) {
  for (const Lane& l : lanes) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

// Per round all of `runs` have, the smallest of their times (none without
// runs).
std::vector<double> MinPerRound(const std::vector<std::vector<double>>& runs) {
  if (runs.empty()) return {};
  size_t n = SIZE_MAX;
  for (const std::vector<double>& r : runs) n = std::min(n, r.size());
  std::vector<double> out(n, INFINITY);
  for (const std::vector<double>& r : runs) {
    for (size_t i = 0; i < n; ++i) out[i] = std::min(out[i], r[i]);
  }
  return out;
}

// Per round all `lanes` have, the fastest of their render times.
std::vector<double> FastestPerRound(const std::vector<const Lane*>& lanes) {
  std::vector<std::vector<double>> runs;
  for (const Lane* l : lanes) runs.push_back(l->timed.t_r);
  return MinPerRound(runs);
}

// Per round: the fastest of `theirs` over the fastest of `ours`.
std::vector<double> FastestRatios(const std::vector<const Lane*>& theirs,
                                  const std::vector<const Lane*>& ours) {
  return PairedRatios(FastestPerRound(theirs), FastestPerRound(ours));
}

// Our single-ray modes: the kd-tree's lane (the report's rules) and, with the
// fast mode, kSingleOriginLane (shadow rays leaving their origin
// triangle untested, from the light, one ray at a time) and kSingleBvhLane
// (the same rays through the BVH over the leaves).
std::vector<const Lane*> OurSingleLanes(const std::vector<Lane>& lanes) {
  std::vector<const Lane*> out = {&lanes.front()};
  if (const Lane* so = FindLane(lanes, kSingleOriginLane)) out.push_back(so);
  if (const Lane* sb = FindLane(lanes, kSingleBvhLane)) out.push_back(sb);
  return out;
}

// Our packet modes: the fast mode and, when timed, kPacketsBvhLane.
std::vector<const Lane*> OurPacketLanes(const std::vector<Lane>& lanes, const Lane& fast) {
  std::vector<const Lane*> out = {&fast};
  if (const Lane* pb = FindLane(lanes, kPacketsBvhLane)) out.push_back(pb);
  return out;
}

// Our single-ray modes and our packet modes.
std::vector<const Lane*> OurLanes(const std::vector<Lane>& lanes, const Lane& fast) {
  std::vector<const Lane*> out = OurSingleLanes(lanes);
  for (const Lane* l : OurPacketLanes(lanes, fast)) out.push_back(l);
  return out;
}

Json LaneTimes(const Lane& l) {
  return {{"T_R", Median(l.timed.t_r)},
          {"T_R_runs", l.timed.t_r},
          {"primary_s", Median(l.timed.t_primary)},
          {"shadow_s", Median(l.timed.t_shadow)},
          {"primary_s_runs", l.timed.t_primary},
          {"shadow_s_runs", l.timed.t_shadow}};
}

}  // namespace

void AddComparisons(const std::vector<Lane>& lanes, bool fast, const EmbreeQuality* quality, bool embree_timed,
                    const TimedBuilds& b, const Json& disagreements, double pixels,
                    const BuiltBvh& bvh, Json* rec) {
  Json& out = *rec;
  out["embree"] = nullptr;
  out["disagreements"] = quality != nullptr ? disagreements : Json();
  out["perf_ratio_kd_over_embree"] = nullptr;
  out["fast_render"] = nullptr;
  const Lane* fl = fast ? FindLane(lanes, kFastLane) : nullptr;
  if (fl != nullptr) {
    out["fast_render"] = LaneTimes(*fl);
    out["fast_render"]["packet_kernel"] = PacketKernelTarget();
    if (const Lane* so = FindLane(lanes, kSingleOriginLane)) {
      out["fast_render"]["single_origin"] = LaneTimes(*so);
    }
    if (const Lane* sb = FindLane(lanes, kSingleBvhLane)) {
      out["fast_render"]["single_bvh"] = LaneTimes(*sb);
      out["fast_render"]["single_bvh"]["build_s"] = bvh.build_s;
      out["fast_render"]["single_bvh"]["bytes"] = bvh.node_bytes;
      out["fast_render"]["single_bvh"]["packet_bytes"] = bvh.packet_bytes;
    }
    if (const Lane* pb = FindLane(lanes, kPacketsBvhLane)) {
      out["fast_render"]["packets_bvh"] = LaneTimes(*pb);
      out["fast_render"]["packets_bvh"]["build_s"] = bvh.build_s;
      out["fast_render"]["packets_bvh"]["bytes"] = bvh.node_bytes;
      out["fast_render"]["packets_bvh"]["packet_bytes"] = bvh.packet_bytes;
    }
  }
  if (quality == nullptr) return;
  const Lane* el = embree_timed ? FindLane(lanes, kEmbreeLane) : nullptr;
  out["embree"] = EmbreeJson(*quality, b, disagreements, el, lanes.front(), pixels);
  out["perf_ratio_kd_over_embree"] = out["embree"]["paired_ratio"];
  if (fl != nullptr && el != nullptr) {
    const std::vector<double> fp = PairedRatios(el->timed.t_r, fl->timed.t_r);
    out["fast_render"]["paired_ratio_runs"] = fp;
    out["fast_render"]["paired_ratio"] = Median(fp);
    const std::vector<double> single = FastestRatios({el}, OurSingleLanes(lanes));
    out["fast_render"]["single_paired_ratio_runs"] = single;
    out["fast_render"]["single_paired_ratio"] = Median(single);
    if (const Lane* ep = FindLane(lanes, kEmbreePacketsLane)) {
      const std::vector<double> pp = PairedRatios(ep->timed.t_r, fl->timed.t_r);
      const std::vector<double> best = FastestRatios({el, ep}, OurLanes(lanes, *fl));
      Json& packets = out["fast_render"]["embree_packets"] = LaneTimes(*ep);
      packets["paired_ratio_runs"] = pp;
      packets["paired_ratio"] = Median(pp);
      out["fast_render"]["best_paired_ratio_runs"] = best;
      out["fast_render"]["best_paired_ratio"] = Median(best);
    }
  }
}

void AddRobustEmbree(const std::vector<Lane>& lanes, const Json& disagreements, Json* rec) {
  const Lane* er = FindLane(lanes, kEmbreeRobustLane);
  const Lane* erp = FindLane(lanes, kEmbreeRobustPacketsLane);
  const Lane* fl = FindLane(lanes, kFastLane);
  if (er == nullptr || erp == nullptr || fl == nullptr || (*rec)["fast_render"].is_null()) return;
  const std::vector<double> single = FastestRatios({er}, OurSingleLanes(lanes));
  const std::vector<double> best = FastestRatios({er, erp}, OurLanes(lanes, *fl));
  Json wrong = Json::object();
  for (const char* kind : {"primary", "shadow", "ao"}) wrong[kind] = disagreements[kind]["other_wrong"];
  (*rec)["fast_render"]["embree_robust"] = {
      {"T_R", Median(er->timed.t_r)},         {"T_R_runs", er->timed.t_r},
      {"packets_T_R", Median(erp->timed.t_r)}, {"packets_T_R_runs", erp->timed.t_r},
      {"single_paired_ratio_runs", single},   {"single_paired_ratio", Median(single)},
      {"best_paired_ratio_runs", best},       {"best_paired_ratio", Median(best)},
      {"disagreements", disagreements["total"]},
      // Of them, rays whose origin lies within rounding of a reported
      // triangle's plane (compare.h): rays spawned from a surface.
      {"disagreements_at_origin", disagreements["at_origin"]},
      {"wrong", wrong}};
}

void AddTriangleBvh(const std::vector<Lane>& lanes, double build_s, size_t bytes, Json* rec) {
  const Lane* ts = FindLane(lanes, kTriangleBvhLane);
  const Lane* tp = FindLane(lanes, kTriangleBvhPacketsLane);
  if (ts == nullptr || tp == nullptr || (*rec)["fast_render"].is_null()) return;
  Json out = {{"single", LaneTimes(*ts)},
              {"packets", LaneTimes(*tp)},
              {"build_s", build_s},
              {"bytes", bytes}};
  const Lane* el = FindLane(lanes, kEmbreeLane);
  const Lane* ep = FindLane(lanes, kEmbreePacketsLane);
  if (el != nullptr && ep != nullptr) {
    const std::vector<double> single = FastestRatios({el}, {ts});
    const std::vector<double> best = FastestRatios({el, ep}, {ts, tp});
    out["single_paired_ratio_runs"] = single;
    out["single_paired_ratio"] = Median(single);
    out["best_paired_ratio_runs"] = best;
    out["best_paired_ratio"] = Median(best);
  }
  (*rec)["fast_render"]["triangle_bvh"] = std::move(out);
}

namespace {

// A pass's times per round: primary (camera) or shadow rays.
const std::vector<double>& PassRuns(const Lane& l, bool shadow) {
  return shadow ? l.timed.t_shadow : l.timed.t_primary;
}

// Per round, the fastest tracing time of `lanes` on the pass, each lane's
// time less `replay`'s; a time that is not positive (within the noise of the
// replay) is left out, and a round with none is 0 (no ratio). As
// experiments/bench_tables.py's per_round_ratio does with render_bench's records.
std::vector<double> FastestTracing(const std::vector<const Lane*>& lanes, const Lane& replay,
                                   bool shadow) {
  std::vector<std::vector<double>> runs;
  for (const Lane* l : lanes) {
    runs.push_back(LessPerRound(PassRuns(*l, shadow), PassRuns(replay, shadow)));
    for (double& t : runs.back()) t = t > 0 ? t : INFINITY;
  }
  std::vector<double> out = MinPerRound(runs);
  for (double& x : out) x = x == INFINITY ? 0 : x;
  return out;
}

Json PassRatio(const std::vector<double>& theirs, const std::vector<double>& ours) {
  std::vector<double> runs;
  for (size_t i = 0; i < theirs.size() && i < ours.size(); ++i) {
    if (theirs[i] > 0 && ours[i] > 0) runs.push_back(theirs[i] / ours[i]);
  }
  return {{"paired_ratio", runs.empty() ? Json() : Json(Median(runs))},
          {"paired_ratio_runs", runs}};
}

}  // namespace

void AddPassComparisons(const std::vector<Lane>& lanes, Json* rec) {
  const Lane* rs = FindLane(lanes, kReplayLane);
  const Lane* rp = FindLane(lanes, kReplayPacketsLane);
  const Lane* el = FindLane(lanes, kEmbreeLane);
  const Lane* ep = FindLane(lanes, kEmbreePacketsLane);
  const Lane* fl = FindLane(lanes, kFastLane);
  if (!rs || !rp || !el || !ep || !fl || (*rec)["fast_render"].is_null()) return;
  Json passes = Json::object();
  for (const bool shadow : {false, true}) {
    // A pass without rays (no light, or no primary hit) has only noise to
    // time: no ratio.
    const bool traced = (shadow ? fl->last.shadow.rays : fl->last.primary.rays) != 0;
    const auto ratio = [&](const std::vector<const Lane*>& theirs,
                           const std::vector<const Lane*>& ours, const Lane& replay) {
      return traced ? PassRatio(FastestTracing(theirs, replay, shadow),
                                FastestTracing(ours, replay, shadow))
                    : PassRatio({}, {});
    };
    const std::string pass = shadow ? "shadow" : "camera";
    passes[pass + "_single"] = ratio({el}, OurSingleLanes(lanes), *rs);
    passes[pass + "_packets"] = ratio({ep}, OurPacketLanes(lanes, *fl), *rp);
  }
  passes["replay_primary_s_runs"] = rs->timed.t_primary;
  passes["replay_shadow_s_runs"] = rs->timed.t_shadow;
  passes["replay_packets_primary_s_runs"] = rp->timed.t_primary;
  passes["replay_packets_shadow_s_runs"] = rp->timed.t_shadow;
  (*rec)["fast_render"]["passes"] = std::move(passes);
}

uint64_t Fnv64(const std::vector<uint8_t>& bytes) { return FnvBytes(bytes.data(), bytes.size()); }

}  // namespace kdtree
