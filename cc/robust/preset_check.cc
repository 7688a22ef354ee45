#include "cc/robust/preset_check.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "absl/status/statusor.h"
#include "absl/strings/numbers.h"
#include "cc/base/json_line.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"
#include "cc/kdtree/triangle_bvh.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace robust {

std::vector<std::string> CheckedPresets() {
  std::vector<std::string> names = {"default"};
  for (const std::string& n : PresetNames()) names.push_back(n);
  // The trees beyond the report that the matrix runs (experiments/matrix.json).
  names.push_back("sah-packet");
  names.push_back("sah-packet-binned");
  return names;
}

absl::StatusOr<Config> ConfigFor(const std::string& name) {
  if (name == "default") return Config();
  return Preset(name);
}

size_t RayStride() {
  static const size_t stride = [] {
    const char* env = std::getenv("KDTREE_ROBUST_RAY_STRIDE");
    size_t k = 1;
    if (env != nullptr && *env != '\0' && (!absl::SimpleAtoi(env, &k) || k == 0)) {
      std::fprintf(stderr, "KDTREE_ROBUST_RAY_STRIDE=%s: not a whole number >= 1\n", env);
      std::exit(2);
    }
    return k;
  }();
  return stride;
}

bool InSample(size_t i) { return (i / kRayPacketSize) % RayStride() == 0; }

// body(begin, end) over [0, n) in oneTBB tasks, each range starting at a
// multiple of the packet size (the packet checks below trace rays
// kRayPacketSize at a time from `begin`); the results do not depend on the split.
void ParallelFor(size_t n, const std::function<void(size_t, size_t)>& body) {
  const size_t packets = (n + kRayPacketSize - 1) / kRayPacketSize;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, packets, 256), [&](const tbb::blocked_range<size_t>& r) {
    body(r.begin() * kRayPacketSize, std::min(n, r.end() * kRayPacketSize));
  });
}

std::vector<Hit> BruteForceHits(const TriangleSoup& soup, const std::vector<Ray>& rays,
                                IntersectionMode mode) {
  const BruteForce bf(soup);
  std::vector<Hit> hits(rays.size());
  ParallelFor(rays.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) hits[i] = bf.Intersect(rays[i], mode);
  });
  return hits;
}

namespace {
bool SameHit(const Hit& a, const Hit& b) {
  if (a.hit() != b.hit()) return false;
  return !a.hit() || (a.tri == b.tri && a.t == b.t && a.u == b.u && a.v == b.v);
}

// The leaf-BVH queries (leaf_bvh.h) through `bvh`, closest and
// any hit, single rays and packets of kRayPacketSize consecutive rays: marks
// in *bad and *bad_any the rays whose answers differ from `reference`.
void CheckLeafBvh(const LeafBvh& bvh, const std::vector<Ray>& rays,
                  const std::vector<Hit>& reference, std::vector<char>* bad,
                  std::vector<char>* bad_any) {
  ParallelFor(rays.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      (*bad)[i] |= !SameHit(IntersectLeafBvh(bvh, rays[i]), reference[i]);
      (*bad_any)[i] |= OccludedLeafBvh(bvh, rays[i]) != reference[i].hit();
    }
    for (size_t i = begin; i < end; i += kRayPacketSize) {
      const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, end - i));
      Hit hits[kRayPacketSize];
      bool occluded[kRayPacketSize];
      IntersectPacketLeafBvh(bvh, &rays[i], n, hits);
      OccludedPacketLeafBvh(bvh, &rays[i], n, nullptr, occluded);
      for (int l = 0; l < n; ++l) {
        (*bad)[i + l] |= !SameHit(hits[l], reference[i + l]);
        (*bad_any)[i + l] |= occluded[l] != reference[i + l].hit();
      }
    }
  });
}

// The counts of r from the rays marked bad.
void Tally(const std::vector<Hit>& reference, const std::vector<char>& bad,
           const std::vector<char>& bad_any, CheckResult* r) {
  for (size_t i = 0; i < reference.size(); ++i) {
    r->hits += reference[i].hit();
    r->mismatches += bad[i];
    r->any_hit_mismatches += bad_any[i];
    if ((bad[i] || bad_any[i]) && r->examples.size() < 5) r->examples.push_back(i);
  }
}
}  // namespace

CheckResult CheckTree(const KdTree& tree, const std::vector<Ray>& rays,
                      const std::vector<Hit>& reference, IntersectionMode mode) {
  CheckResult r;
  r.mode = mode;
  r.rays = rays.size();
  std::vector<char> bad(rays.size(), 0), bad_any(rays.size(), 0);
  TraversalOptions options;
  options.mode = mode;
  // Any hit searched from the ray's end too (the renderer's secondary rays).
  TraversalOptions from_end = options;
  from_end.from_end = true;
  ParallelFor(rays.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Hit got = Intersect(tree, rays[i], WithTest(mode));
      bad[i] = !SameHit(got, reference[i]);
      bad_any[i] = Occluded(tree, rays[i], WithTest(mode)) != reference[i].hit();
      bad_any[i] |= Occluded(tree, rays[i], from_end) != reference[i].hit();
    }
    // The packet traversal (ray_packet.h) on consecutive rays, kRayPacketSize
    // (16) at a time:
    // each lane must give the same answers.
    for (size_t i = begin; i < end; i += kRayPacketSize) {
      const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, end - i));
      Hit hits[kRayPacketSize];
      bool occluded[kRayPacketSize], occluded_end[kRayPacketSize];
      IntersectPacket(tree, &rays[i], n, hits, options);
      OccludedPacket(tree, &rays[i], n, nullptr, occluded, options);
      OccludedPacket(tree, &rays[i], n, nullptr, occluded_end, from_end);
      for (int l = 0; l < n; ++l) {
        bad[i + l] |= !SameHit(hits[l], reference[i + l]);
        bad_any[i + l] |= occluded[l] != reference[i + l].hit();
        bad_any[i + l] |= occluded_end[l] != reference[i + l].hit();
      }
    }
  });
  // The BVH over the tree's leaves (leaf_bvh.h), watertight test only.
  // (No budget: it fails only past 2^31 packets, which no check reaches;
  // should it, every ray counts as a mismatch.)
  if (mode == IntersectionMode::kWatertight) {
    absl::StatusOr<LeafBvh> bvh = BuildLeafBvh(tree);
    if (bvh.ok()) {
      CheckLeafBvh(*bvh, rays, reference, &bad, &bad_any);
    } else {
      std::fprintf(stderr, "preset_check: %s\n", bvh.status().ToString().c_str());
      std::fill(bad.begin(), bad.end(), 1);
      std::fill(bad_any.begin(), bad_any.end(), 1);
    }
  }
  Tally(reference, bad, bad_any, &r);
  return r;
}

CheckResult CheckTriangleBvh(const TriangleSoup& soup, const std::vector<Ray>& rays,
                             const std::vector<Hit>& reference) {
  CheckResult r;
  r.preset = kTriangleBvhRow;
  r.rays = rays.size();
  const absl::StatusOr<LeafBvh> tb = BuildTriangleBvh(soup);
  if (!tb.ok()) {
    std::printf("%s: build failed: %s\n", kTriangleBvhRow, tb.status().ToString().c_str());
    r.mismatches = rays.size();  // a failed build fails the check
    return r;
  }
  std::vector<char> bad(rays.size(), 0), bad_any(rays.size(), 0);
  CheckLeafBvh(*tb, rays, reference, &bad, &bad_any);
  Tally(reference, bad, bad_any, &r);
  return r;
}

std::string ResultJson(const std::string& case_name, const CheckResult& r) {
  const nlohmann::ordered_json j = {{"case", case_name},
                                    {"preset", r.preset},
                                    {"mode", IntersectionModeName(r.mode)},
                                    {"rays", r.rays},
                                    {"hits", r.hits},
                                    {"mismatches", r.mismatches},
                                    {"any_hit_mismatches", r.any_hit_mismatches},
                                    {"required", !r.informational}};
  return JsonLine(j);
}

namespace {

// A ray's origin, direction, tmin and tmax in hexadecimal floats: enough to
// replay a failure.
std::string RayText(const Ray& ray) {
  char text[320];
  std::snprintf(text, sizeof(text), "origin (%a, %a, %a) dir (%a, %a, %a) tmin %a tmax %a",
                ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z,
                ray.tmin, ray.tmax);
  return text;
}

void PrintExamples(const std::string& case_name, const std::string& preset, const KdTree& tree,
                   const std::vector<Ray>& rays, const std::vector<Hit>& reference,
                   const CheckResult& r) {
  for (size_t i : r.examples) {
    const Ray& ray = rays[i];
    const Hit got = Intersect(tree, ray, WithTest(r.mode)), want = reference[i];
    std::printf("%s/%s/%s mismatch: ray %zu %s: kd-tree tri %d t %.9g (any-hit %d), "
                "brute force tri %d t %.9g\n",
                case_name.c_str(), preset.c_str(), IntersectionModeName(r.mode), i,
                RayText(ray).c_str(), got.hit() ? static_cast<int>(got.tri) : -1, got.t,
                Occluded(tree, ray, WithTest(r.mode)) ? 1 : 0,
                want.hit() ? static_cast<int>(want.tri) : -1, want.t);
  }
}

std::vector<CheckResult> Check(const std::string& case_name, const TriangleSoup& soup,
                               const std::vector<Ray>& rays,
                               const std::vector<IntersectionMode>& modes,
                               const std::vector<const std::vector<Hit>*>& references,
                               const CheckOptions& options) {
  std::vector<std::string> names = options.presets.empty() ? CheckedPresets() : options.presets;
  if (options.include_seed) names.push_back("pruning-seed");
  std::vector<CheckResult> results;
  for (const std::string& name : names) {
    absl::StatusOr<Config> config = ConfigFor(name);
    absl::StatusOr<KdTree> tree =
        config.ok() ? BuildKdTree(soup, *config) : absl::StatusOr<KdTree>(config.status());
    for (size_t m = 0; m < modes.size(); ++m) {
      CheckResult r;
      if (!tree.ok()) {
        std::printf("%s/%s: build failed: %s\n", case_name.c_str(), name.c_str(),
                    tree.status().ToString().c_str());
        r.mode = modes[m];
        r.rays = rays.size();
        r.mismatches = rays.size();  // a failed build fails the check
      } else {
        r = CheckTree(*tree, rays, *references[m], modes[m]);
        PrintExamples(case_name, name, *tree, rays, *references[m], r);
      }
      r.preset = name;
      r.informational = name == "pruning-seed";
      std::printf("ROBUST_JSON %s\n", ResultJson(case_name, r).c_str());
      results.push_back(std::move(r));
    }
  }
  for (size_t m = 0; m < modes.size() && options.triangle_bvh; ++m) {
    if (modes[m] != IntersectionMode::kWatertight) continue;
    CheckResult r = CheckTriangleBvh(soup, rays, *references[m]);
    for (size_t i : r.examples) {
      std::printf("%s/%s mismatch: ray %zu %s\n", case_name.c_str(), kTriangleBvhRow, i,
                  RayText(rays[i]).c_str());
    }
    std::printf("ROBUST_JSON %s\n", ResultJson(case_name, r).c_str());
    results.push_back(std::move(r));
  }
  std::fflush(stdout);
  return results;
}

}  // namespace

std::vector<CheckResult> CheckAllPresets(const std::string& case_name, const TriangleSoup& soup,
                                         const std::vector<Ray>& rays, IntersectionMode mode,
                                         const std::vector<Hit>* reference,
                                         const CheckOptions& options) {
  const std::vector<Ray> sample = Sample(rays);
  const std::vector<Hit> sampled =
      reference == nullptr ? BruteForceHits(soup, sample, mode) : Sample(*reference);
  return Check(case_name, soup, sample, {mode}, {&sampled}, options);
}

std::vector<CheckResult> CheckAllPresets(const std::string& case_name, const TriangleSoup& soup,
                                         const std::vector<Ray>& rays,
                                         const std::vector<IntersectionMode>& modes,
                                         const CheckOptions& options) {
  const std::vector<Ray> sample = Sample(rays);
  std::vector<std::vector<Hit>> computed;
  for (IntersectionMode mode : modes) computed.push_back(BruteForceHits(soup, sample, mode));
  std::vector<const std::vector<Hit>*> references;
  for (const auto& c : computed) references.push_back(&c);
  return Check(case_name, soup, sample, modes, references, options);
}

std::vector<std::vector<float>> SplitValues(const KdTree& tree) {
  std::vector<std::vector<float>> s(3);
  for (const KdNode& n : tree.nodes) {
    if (!n.is_leaf()) s[n.axis()].push_back(n.split);
  }
  for (auto& v : s) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  return s;
}

std::vector<float> VertexCoordinates(const TriangleSoup& soup, int axis) {
  std::vector<float> v;
  v.reserve(soup.v.size());
  for (const Vec3& p : soup.v) v.push_back(p[axis]);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::vector<float> SortedUnion(const std::vector<std::vector<float>>& parts) {
  std::vector<float> v;
  for (const auto& p : parts) v.insert(v.end(), p.begin(), p.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace robust
}  // namespace kdtree
