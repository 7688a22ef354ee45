#include "cc/kdtree/bvh_check.h"

#include <algorithm>
#include <cstdint>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"

namespace kdtree {
namespace testing {

int PacketMismatches(const KdTree& tree, const LeafBvh& bvh, const std::vector<Ray>& rays) {
  int bad = 0;
  for (size_t i = 0; i < rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, rays.size() - i));
    Hit hits[kRayPacketSize];
    bool occluded[kRayPacketSize];
    IntersectPacketLeafBvh(bvh, &rays[i], n, hits);
    OccludedPacketLeafBvh(bvh, &rays[i], n, nullptr, occluded);
    for (int l = 0; l < n; ++l) {
      const Hit want = Intersect(tree, rays[i + l]);
      bad += !BitwiseSameHit(hits[l], want) + (occluded[l] != want.hit());
    }
  }
  return bad;
}

BvhMismatches CompareWithKdTree(const TriangleSoup& soup, const KdTree& tree, const LeafBvh& bvh,
                                const std::vector<Ray>& rays, int brute_force_every) {
  BvhMismatches m;
  const BruteForce bf(soup);
  const Vec3 light = tree.bounds.hi + tree.bounds.Extent() * 0.5f;
  TraversalOptions from_end;
  from_end.from_end = true;
  std::vector<Ray> shadow_rays;
  std::vector<uint32_t> shadow_origins;
  std::vector<char> shadow_blocked;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit want = Intersect(tree, rays[i]);
    const Hit got = IntersectLeafBvh(bvh, rays[i]);
    m.closest += !BitwiseSameHit(got, want);
    m.any += OccludedLeafBvh(bvh, rays[i]) != want.hit();
    if (i % brute_force_every == 0) m.closest += !BitwiseSameHit(got, bf.Intersect(rays[i]));
    if (!want.hit()) continue;
    ++m.hits;
    const Ray s = ShadowRayFromHit(soup, want, light);
    TraversalOptions o = from_end;
    o.origin_tri = want.tri;
    const bool blocked = Occluded(tree, s, o);
    m.shadow += OccludedLeafBvh(bvh, s, want.tri) != blocked;
    m.shadows += blocked;
    shadow_rays.push_back(s);
    shadow_origins.push_back(want.tri);
    shadow_blocked.push_back(blocked);
  }
  // Packets of 16 consecutive rays (coherent camera rows among them), each
  // lane against its single ray, bit for bit.
  m.packets = PacketMismatches(tree, bvh, rays);
  for (size_t i = 0; i < shadow_rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, shadow_rays.size() - i));
    bool occluded[kRayPacketSize];
    OccludedPacketLeafBvh(bvh, &shadow_rays[i], n, &shadow_origins[i], occluded);
    for (int l = 0; l < n; ++l) m.packets += occluded[l] != (shadow_blocked[i + l] != 0);
  }
  return m;
}

}  // namespace testing
}  // namespace kdtree
