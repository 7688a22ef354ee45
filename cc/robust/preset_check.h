// The check every adversarial test runs: each kd-tree preset against the
// brute-force reference, in the same intersection mode, ray by ray.
//
// A mismatch is any difference in the closest hit: hit versus miss, another
// triangle, or another t (bitwise). Both tracers use the same triangle test and
// the same tie rule (Closer() in ray.h), so a correct traversal reproduces the
// reference exactly; "0 mismatches" is the only pass. The any-hit query
// (Occluded) is checked against the reference's closest hit as well, front to
// back and from the ray's end (TraversalOptions::from_end), single rays and
// packets; with the watertight test, the BVH over the tree's leaves too
// (cc/kdtree/leaf_bvh.h: both queries, single rays and packets).
//
// Every result is also printed as one JSON line prefixed "ROBUST_JSON " (case,
// preset, mode, rays, hits, mismatches), collected for the report.
#ifndef KDTREE_CC_ROBUST_PRESET_CHECK_H_
#define KDTREE_CC_ROBUST_PRESET_CHECK_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/geometry/intersection_mode.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/tree.h"

namespace kdtree {
namespace robust {

struct CheckResult {
  std::string preset;
  IntersectionMode mode = IntersectionMode::kWatertight;
  size_t rays = 0;
  size_t hits = 0;                  // reference hits
  size_t mismatches = 0;            // closest hit differs (hit, triangle or t)
  size_t any_hit_mismatches = 0;    // Occluded() differs from the reference
  std::vector<size_t> examples;     // a few mismatching ray indices
  bool informational = false;       // not required to pass (seed-compatible)
};

// "default" (Config(): the report's environment file), the nine
// PresetNames(), then the two trees beyond the report that the experiment
// matrix runs (sah-packet, sah-packet-binned); these must all pass.
std::vector<std::string> CheckedPresets();
// Config for a name from CheckedPresets() or "pruning-seed".
absl::StatusOr<Config> ConfigFor(const std::string& name);

// The suite's ray sample, for a quick reproduction: with
// KDTREE_ROBUST_RAY_STRIDE=k in the environment (cc/robust/robust_suite.py
// sets it from the profile and records it), every check keeps every k-th
// group of kRayPacketSize consecutive rays (one packet) of its case and drops
// the others; unset or 1 keeps every ray (bazel test, the full profile). Any
// other value than a whole number >= 1 stops the process, naming it.
size_t RayStride();
// Whether ray i of a case is in the sample.
bool InSample(size_t i);
// The elements of v whose index is InSample().
template <typename T>
std::vector<T> Sample(const std::vector<T>& v) {
  if (RayStride() == 1) return v;
  std::vector<T> kept;
  for (size_t i = 0; i < v.size(); ++i) {
    if (InSample(i)) kept.push_back(v[i]);
  }
  return kept;
}

// Runs body(begin, end) over [0, n) split across all hardware threads.
void ParallelFor(size_t n, const std::function<void(size_t, size_t)>& body);

// Brute-force closest hits of every ray (all triangles, all threads).
std::vector<Hit> BruteForceHits(const TriangleSoup& soup, const std::vector<Ray>& rays,
                                IntersectionMode mode);

// One tree against a precomputed reference: the single-ray queries, and the
// packet traversal (cc/kdtree/ray_packet.h) on consecutive groups of
// kRayPacketSize (16) rays;
// a ray mismatches when either differs.
CheckResult CheckTree(const KdTree& tree, const std::vector<Ray>& rays,
                      const std::vector<Hit>& reference, IntersectionMode mode);

// The row of the BVH of whole triangles (cc/kdtree/triangle_bvh.h): the
// baseline the report sets beside the kd-tree against Embree, not a preset.
inline constexpr char kTriangleBvhRow[] = "triangle-bvh";

// The baseline over `soup`, with the watertight test, against `reference`:
// closest and any hit, single rays and packets (preset kTriangleBvhRow).
CheckResult CheckTriangleBvh(const TriangleSoup& soup, const std::vector<Ray>& rays,
                             const std::vector<Hit>& reference);

struct CheckOptions {
  // Also run the seed-compatible "pruning-seed" preset, reported but not
  // required to pass (it loses triangles lying in split planes by design).
  bool include_seed = false;
  // Build every tree with these options only (a subset of CheckedPresets()).
  std::vector<std::string> presets;
  // Also check the baseline (CheckTriangleBvh) in the watertight mode, as a
  // row of its own after the presets'.
  bool triangle_bvh = true;
};

// Builds every preset over `soup` and checks it on the Sample() of `rays`
// against `reference` (computed with BruteForceHits when null). Prints one ROBUST_JSON line each.
std::vector<CheckResult> CheckAllPresets(const std::string& case_name, const TriangleSoup& soup,
                                         const std::vector<Ray>& rays, IntersectionMode mode,
                                         const std::vector<Hit>* reference = nullptr,
                                         const CheckOptions& options = CheckOptions());

// The same for several modes: each tree is built once and checked in every
// mode against that mode's brute-force reference.
std::vector<CheckResult> CheckAllPresets(const std::string& case_name, const TriangleSoup& soup,
                                         const std::vector<Ray>& rays,
                                         const std::vector<IntersectionMode>& modes,
                                         const CheckOptions& options = CheckOptions());

// Both modes, watertight first.
inline const std::vector<IntersectionMode>& BothModes() {
  static const auto* modes = new std::vector<IntersectionMode>{IntersectionMode::kWatertight,
                                                               IntersectionMode::kFast};
  return *modes;
}

// The JSON line of a result.
std::string ResultJson(const std::string& case_name, const CheckResult& r);

// Every split value of the tree, per axis, sorted and unique.
std::vector<std::vector<float>> SplitValues(const KdTree& tree);

// Sorted unique values of coordinate `axis` over the soup's vertices.
std::vector<float> VertexCoordinates(const TriangleSoup& soup, int axis);

// Sorted union of the vectors, duplicates removed.
std::vector<float> SortedUnion(const std::vector<std::vector<float>>& parts);

}  // namespace robust
}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_PRESET_CHECK_H_
