#include "cc/bench/ray_classes.h"

#include <algorithm>
#include <chrono>
#include <cstddef>

#include "cc/base/median.h"
#include "cc/kdtree/traversal.h"

namespace kdtree {
namespace bench {
namespace {

enum Class { kNoNode, kMiss, kHit, kShadow, kAo, kNumClasses };
constexpr const char* kNames[kNumClasses] = {"camera_no_node", "camera_miss", "camera_hit",
                                             "shadow", "ao"};

// Whether the traversal of `ray` visits any node of `tree`.
bool ReachesNode(const KdTree& tree, const Ray& ray) {
  TraversalCounters c;
  Intersect(tree, ray, TraversalOptions(), &c);
  return c.inner_visits + c.leaf_visits > 0;
}

// Seconds for `tracer` to trace every ray of `c` once; `sink` keeps the
// answers alive.
double TraceClass(const RayClass& c, const RenderVariant& v, uint64_t* sink) {
  const auto start = std::chrono::steady_clock::now();
  uint64_t acc = 0;
  if (c.any_hit) {
    for (size_t i = 0; i < c.rays.size(); ++i) {
      acc += v.tracer->Occluded(c.rays[i], v.skip_origin ? c.origin_tris[i] : kNoHit);
    }
  } else {
    for (const Ray& r : c.rays) acc += v.tracer->Intersect(r).tri;
  }
  const std::chrono::duration<double> s = std::chrono::steady_clock::now() - start;
  *sink += acc;
  return s.count();
}

}  // namespace

std::vector<RayClass> ClassifyRays(const std::vector<RayRecord>& recs, const KdTree& tree) {
  std::vector<RayClass> classes(kNumClasses);
  for (int k = 0; k < kNumClasses; ++k) {
    classes[k].name = kNames[k];
    classes[k].any_hit = k >= kShadow;
  }
  std::vector<uint32_t> pixel_tri;  // each pixel's primary hit
  for (const RayRecord& r : recs) {
    if (r.kind != RayKind::kPrimary) continue;
    if (r.pixel >= pixel_tri.size()) pixel_tri.resize(r.pixel + 1, kNoHit);
    pixel_tri[r.pixel] = r.tri;
  }
  for (const RayRecord& r : recs) {
    if (r.kind == RayKind::kPrimary) {
      const Class k = r.tri != kNoHit ? kHit : ReachesNode(tree, r.ray()) ? kMiss : kNoNode;
      classes[k].rays.push_back(r.ray());
      continue;
    }
    RayClass& c = classes[r.kind == RayKind::kShadow ? kShadow : kAo];
    c.rays.push_back(r.ray());
    c.origin_tris.push_back(r.pixel < pixel_tri.size() ? pixel_tri[r.pixel] : kNoHit);
  }
  classes.erase(std::remove_if(classes.begin(), classes.end(),
                               [](const RayClass& c) { return c.rays.empty(); }),
                classes.end());
  return classes;
}

Json TimeRayClasses(const std::vector<RayClass>& classes,
                    const std::vector<RenderVariant>& tracers, const std::string& reference,
                    int warmup, int rounds) {
  const size_t n = tracers.size();
  // ns[c][t]: per round.
  std::vector<std::vector<std::vector<double>>> ns(classes.size(),
                                                    std::vector<std::vector<double>>(n));
  uint64_t sink = 0;
  for (int round = -warmup; round < rounds; ++round) {
    for (size_t c = 0; c < classes.size(); ++c) {
      for (size_t k = 0; k < n; ++k) {
        const size_t t = (k + static_cast<size_t>(round + warmup)) % n;
        const double s = TraceClass(classes[c], tracers[t], &sink);
        if (round >= 0) ns[c][t].push_back(1e9 * s / classes[c].rays.size());
      }
    }
  }
  const auto ref = std::find_if(tracers.begin(), tracers.end(),
                                [&](const RenderVariant& v) { return v.name == reference; });
  // The answers' sum, so that no trace is optimised away.
  Json out = {{"rounds", rounds}, {"warmup", warmup}, {"checksum", sink},
              {"classes", Json::object()}};
  for (size_t c = 0; c < classes.size(); ++c) {
    Json ns_runs = Json::object(), ns_median = Json::object(), over = Json::object();
    for (size_t t = 0; t < n; ++t) {
      ns_runs[tracers[t].name] = ns[c][t];
      ns_median[tracers[t].name] = Median(ns[c][t]);
      if (ref == tracers.end() || tracers[t].name == reference) continue;
      const std::vector<double> ratios = PairedRatios(ns[c][ref - tracers.begin()], ns[c][t]);
      if (ratios.empty()) continue;
      over[tracers[t].name] = {{"median", Median(ratios)},
                               {"min", *std::min_element(ratios.begin(), ratios.end())},
                               {"max", *std::max_element(ratios.begin(), ratios.end())}};
    }
    Json entry = {{"rays", classes[c].rays.size()},
                  {"ns_runs", std::move(ns_runs)},
                  {"ns_per_ray", std::move(ns_median)}};
    if (ref != tracers.end()) entry[reference + "_over"] = std::move(over);
    out["classes"][classes[c].name] = std::move(entry);
  }
  return out;
}

}  // namespace bench
}  // namespace kdtree
