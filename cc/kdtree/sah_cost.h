// The cost of a candidate split plane, shared by the split strategies.
//
// Two models (Config::full_sah):
//  - the report's relaxed SAH (section "Binning SAH strategy", after Havran &
//    Bittner 2002): C = SA_L N_L + SA_R N_R, in float, in this exact order
//    (the report's presets depend on it);
//  - the full SAH of Wald & Havran, "On building fast kd-trees for ray tracing,
//    and on doing that in O(N log N)", IEEE RT 2006, eq. (3)-(4):
//      C = K_T + lambda(p) K_I (SA_L N_L + SA_R N_R) / SA,
//      lambda(p) = empty_bonus (0.8) if N_L == 0 or N_R == 0, else 1,
//    with K_T = 15, K_I = 20 by default (Config); a node is a leaf when no
//    plane is cheaper than C_leaf = K_I N. With Config::sah_packet = P > 1,
//    every N above counts packets, ceil(N / P) (lambda still asks N == 0).
#ifndef KDTREE_CC_KDTREE_SAH_COST_H_
#define KDTREE_CC_KDTREE_SAH_COST_H_

#include <cmath>
#include <cstddef>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/config.h"

namespace kdtree {

// n references as the full SAH counts them: n, or its packets (sah_packet).
inline double Packets(double n, const Config& config) {
  return config.sah_packet == 1 ? n : std::ceil(n / config.sah_packet);
}

// Cost of splitting `box` at `axis = plane` with n_left / n_right references.
inline float SplitCost(const AABB& box, int axis, float plane, float n_left, float n_right,
                       const Config& config) {
  const float sa_l = box.LeftOf(axis, plane).SurfaceArea();
  const float sa_r = box.RightOf(axis, plane).SurfaceArea();
  if (!config.full_sah) return sa_l * n_left + sa_r * n_right;
  const double sa = box.SurfaceArea();
  const double lambda = (n_left == 0.0f || n_right == 0.0f) ? config.empty_bonus : 1.0;
  const double bl = Packets(n_left, config), br = Packets(n_right, config);
  const double rel = sa > 0 ? (double(sa_l) * bl + double(sa_r) * br) / sa : bl + br;
  return static_cast<float>(config.traversal_cost + lambda * config.intersection_cost * rel);
}

// Cost of making a leaf of n references (full SAH).
inline double LeafCost(size_t n, const Config& config) {
  return config.intersection_cost * Packets(static_cast<double>(n), config);
}

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_SAH_COST_H_
