// Pieces of kdrt's record (cc/tools/kdrt_record.schema.json declares every
// field): the configuration, per-ray traversal counts and tree statistics, a
// timed lane's render figures, the fast mode's and Embree's objects, and the
// image's hash.
#ifndef KDTREE_CC_TOOLS_KDRT_RECORD_H_
#define KDTREE_CC_TOOLS_KDRT_RECORD_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/embree/embree_tracer.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/stats.h"
#include "cc/render/traversal_counts.h"
#include "cc/tools/timed_build.h"
#include "cc/tools/timed_render.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// The configuration's fields as the record shows them.
nlohmann::ordered_json ConfigJson(const Config& c);

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

// Adds, in the record's order, N_IT and N_TR (per ray, all kinds), the
// counters per ray kind ("traversal"), counting_mismatches, the tree's
// statistics (stats.h StatsToJson) and the render's hit counts.
void AddCountsAndStats(const RayCounts& counts, const TreeStats& stats, const RenderResult& r,
                       nlohmann::ordered_json* rec);

// The timed lanes' names, which kdrt gives them and the record finds them
// by: the renderer's fastest mode (RenderOptions::packets and skip_origin)
// and our other single-ray mode, the fast mode's secondary rays one ray at a
// time (skip_origin, no packets), both with --fast_render; Embree's single
// rays and packets, at its default flags and built robust.
inline constexpr char kFastLane[] = "kd-tree fast";
inline constexpr char kSingleOriginLane[] = "kd-tree single origin";
// kSingleOriginLane's rays through the BVH over the tree's leaves
// (cc/kdtree/leaf_bvh.h): our third single-ray mode.
inline constexpr char kSingleBvhLane[] = "kd-tree single bvh";
// The fast mode's rays in its packets through the same BVH
// (leaf_bvh_packet_kernel.cc): our second packet mode.
inline constexpr char kPacketsBvhLane[] = "kd-tree packets bvh";
// The same two modes' rays through a BVH of whole triangles, no kd-tree
// (cc/kdtree/triangle_bvh.h; kdrt --triangle_bvh): a baseline, not one of our
// modes, so no ratio of ours takes it.
inline constexpr char kTriangleBvhLane[] = "triangle bvh single";
inline constexpr char kTriangleBvhPacketsLane[] = "triangle bvh packets";
inline constexpr char kEmbreeLane[] = "embree";
inline constexpr char kEmbreePacketsLane[] = "embree packets";
inline constexpr char kEmbreeRobustLane[] = "embree robust";
inline constexpr char kEmbreeRobustPacketsLane[] = "embree robust packets";
// The kd-tree's answers replayed (replay_tracer.h), single rays and in the
// fast mode's packets: the renderer's own work on each pass.
inline constexpr char kReplayLane[] = "replay";
inline constexpr char kReplayPacketsLane[] = "replay packets";

// The BVH over the kd-tree's leaves (cc/kdtree/leaf_bvh.h) that kdrt's
// kSingleBvhLane and kPacketsBvhLane trace: its build's seconds (from the
// finished tree) and its bytes, kept after it is freed.
struct BuiltBvh {
  double build_s = 0;
  size_t node_bytes = 0;    // LeafBvh::node_bytes
  size_t packet_bytes = 0;  // LeafBvh::packet_bytes: its own leaf packets
};

// Adds "embree", "disagreements", "perf_ratio_kd_over_embree" and
// "fast_render": lanes are the timed lanes (the kd-tree's first; with `fast`
// kFastLane and kSingleOriginLane; Embree's when `embree_timed`); `quality`
// is null without Embree. Single rays against single rays take per round the
// fastest of our single-ray lanes (the first, kSingleOriginLane and
// kSingleBvhLane, whose BVH is `bvh`), best mode against best mode the
// fastest of ours (the fast mode and kPacketsBvhLane too) over the faster of
// Embree's two.
void AddComparisons(const std::vector<Lane>& lanes, bool fast, const EmbreeQuality* quality,
                    bool embree_timed, const TimedBuilds& b, const nlohmann::ordered_json& disagreements,
                    double pixels, const BuiltBvh& bvh, nlohmann::ordered_json* rec);

// With the lanes kEmbreeRobustLane and kEmbreeRobustPacketsLane (Embree built
// with RTC_SCENE_FLAG_ROBUST, timed in the same rounds): adds
// fast_render.embree_robust, their times, their single rays against our
// faster single-ray lane and the best mode of each against the other's (as
// AddComparisons pairs them), per round, and per ray kind the rays exact
// arithmetic proves it wrong on (`disagreements`: its
// Disagreements::ToJson against the kd-tree).
void AddRobustEmbree(const std::vector<Lane>& lanes, const nlohmann::ordered_json& disagreements,
                     nlohmann::ordered_json* rec);

// With the lanes kTriangleBvhLane and kTriangleBvhPacketsLane: adds
// fast_render.triangle_bvh, their times, the hierarchy's build seconds and
// bytes, and (with Embree's two lanes) Embree's single rays over the
// baseline's and Embree's best mode over the baseline's faster lane, paired
// per round as AddComparisons pairs ours: what the kd-tree's structure
// costs, the kernels being the same.
void AddTriangleBvh(const std::vector<Lane>& lanes, double build_s, size_t bytes,
                    nlohmann::ordered_json* rec);

// With the replay lanes (kReplayLane, kReplayPacketsLane, one thread) and
// Embree's two: adds fast_render.passes, where the gap is, per pass (camera
// rays, shadow rays): each lane's pass time less its mode's replay in the
// same round (its tracing time alone), Embree's over ours, paired per round;
// single rays (Embree's against the fastest of our single-ray lanes) and
// packets (Embree's 16-ray packets against the fast mode). A round where
// either tracing time is not positive (a pass too short to time) gives no
// ratio, and neither does a pass without rays (no light, or no primary hit).
void AddPassComparisons(const std::vector<Lane>& lanes, nlohmann::ordered_json* rec);

// FNV-1a 64 of the image's bytes (image_fnv64).
uint64_t Fnv64(const std::vector<uint8_t>& bytes);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_RECORD_H_
