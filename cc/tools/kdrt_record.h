// Pieces of kdrt's record (cc/tools/kdrt_record.schema.json declares every
// field): per-ray traversal counts, a timed lane's render figures, Embree's
// object, and the image's hash.
#ifndef KDTREE_CC_TOOLS_KDRT_RECORD_H_
#define KDTREE_CC_TOOLS_KDRT_RECORD_H_

#include <cstdint>
#include <vector>

#include "cc/embree/embree_tracer.h"
#include "cc/render/traversal_counts.h"
#include "cc/tools/timed_build.h"
#include "cc/tools/timed_render.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// {"rays", "N_IT", "N_TR", "leaves"}: the counters per ray.
nlohmann::ordered_json TraversalJson(const TraversalCounters& c);

// Adds a timed lane's T_R (median) and its runs, its warm-up, perf (the
// report's krays/s: `pixels` primary rays per second of T_R) and every ray
// per second to *j.
void AddRenderTimes(const Lane& lane, double pixels, nlohmann::ordered_json* j);

// The record's "embree" object: its quality, builds and the comparison of
// every ray (`disagreements`: compare.h's Disagreements::ToJson), and with
// `el` (Embree's lane in the timed rounds) its timed renders and the ratios
// paired with the kd-tree's lane `kl`; with `el` null (Embree built once,
// untimed) the timings are null and timed is false.
nlohmann::ordered_json EmbreeJson(EmbreeQuality quality, const TimedBuilds& b,
                                  const nlohmann::ordered_json& disagreements, const Lane* el,
                                  const Lane& kl, double pixels);

// FNV-1a 64 of the image's bytes (image_fnv64).
uint64_t Fnv64(const std::vector<uint8_t>& bytes);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_RECORD_H_
