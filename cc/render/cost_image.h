// Per-pixel traversal cost: the report's N_TR (inner nodes visited) and N_IT
// (triangle tests) of every ray, summed per pixel and per ray kind, the data
// of the cost images the kd-tree literature draws to show *where* a tree is
// expensive (e.g. Wald, "Realtime Ray Tracing and Interactive Global
// Illumination", PhD thesis 2004, ch. 7; Havran, "Heuristic Ray Shooting
// Algorithms", PhD thesis 2000). Filled by the counting pass
// (traversal_counts.h) from the recorded rays, so the timed render never
// counts; written as a NumPy .npy file for analysis/cost_images.py.
#ifndef KDTREE_CC_RENDER_COST_IMAGE_H_
#define KDTREE_CC_RENDER_COST_IMAGE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "cc/render/ray_record.h"

namespace kdtree {

// Three counts per ray kind: rays, inner nodes visited, triangle tests.
inline constexpr int kCostPerKind = 3;
inline constexpr int kCostChannels = kCostPerKind * kNumRayKinds;
enum CostCount { kCostRays = 0, kCostInnerVisits = 1, kCostTriangleTests = 2 };

struct CostImage {
  int width = 0;
  int height = 0;
  // Row-major, then channel: index ((y * width + x) * kCostChannels) +
  // kCostPerKind * kind + CostCount.
  std::vector<uint32_t> counts;

  CostImage() = default;
  CostImage(int w, int h)
      : width(w), height(h), counts(static_cast<size_t>(w) * h * kCostChannels, 0) {}
  // Adds one ray's counts to its pixel (saturating at 2^32 - 1).
  void Add(uint32_t pixel, RayKind kind, uint64_t inner_visits, uint64_t triangle_tests);
  uint32_t at(int x, int y, RayKind kind, CostCount which) const {
    return counts[(static_cast<size_t>(y) * width + x) * kCostChannels +
                  kCostPerKind * static_cast<int>(kind) + which];
  }
};

// A gzip-compressed NumPy file (format 1.0, dtype '<u4', shape (height,
// width, 3, 3): [..., kind, {rays, inner visits, triangle tests}], kinds
// primary, shadow, ao); numpy.load(gzip.open(path)) reads it. Compressed because most
// pixels of most scenes repeat their neighbours' counts: 23 MB raw at
// 800x800, about 0.5-2 MB written.
absl::Status WriteCostImageNpyGz(const std::string& path, const CostImage& image);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_COST_IMAGE_H_
