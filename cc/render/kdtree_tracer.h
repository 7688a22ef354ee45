// Tracer adapters for the kd-tree (non-counting fast path of
// cc/kdtree/traversal.h) and for the brute-force reference.
#ifndef KDTREE_CC_RENDER_KDTREE_TRACER_H_
#define KDTREE_CC_RENDER_KDTREE_TRACER_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"
#include "cc/kdtree/tree.h"
#include "cc/kdtree/triangle_bvh.h"
#include "cc/render/tracer.h"

namespace kdtree {

// Traces with the kd-tree's fast path (no counters but, when asked,
// CountPackets's). `tree` must outlive it.
class KdTreeTracer : public Tracer {
 public:
  explicit KdTreeTracer(const KdTree& tree) : tree_(tree) {}
  // With traversal options (intersection mode, origin triangle, order;
  // traversal.h).
  KdTreeTracer(const KdTree& tree, const TraversalOptions& options)
      : tree_(tree), options_(options) {}
  std::string name() const override { return "kdtree"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override;
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override;
  // The kd-tree's packet traversal (cc/kdtree/ray_packet.h).
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override;
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override;
  // From now on, what the packet traversal does goes into *closest
  // (IntersectPacket) and *any (OccludedPacket); null: not counted. The
  // counters are not shared safely between threads: render with one.
  void CountPackets(PacketCounters* closest, PacketCounters* any) {
    closest_ = closest;
    any_ = any;
  }

 protected:
  PacketCounters* closest_counters() const { return closest_; }
  PacketCounters* any_counters() const { return any_; }

 private:
  const KdTree& tree_;
  TraversalOptions options_;
  PacketCounters* closest_ = nullptr;
  PacketCounters* any_ = nullptr;
};

// The kd-tree's leaves under a BVH (cc/kdtree/leaf_bvh.h), single rays and
// packets (the same answers as KdTreeTracer's; CountPackets counts the
// packets through the BVH).
// Secondary rays that name their origin triangle leave it untested, as in
// KdTreeTracer::Occluded. `tree` must outlive it.
class KdTreeBvhTracer : public KdTreeTracer {
 public:
  KdTreeBvhTracer(const KdTree& tree, LeafBvh bvh) : KdTreeTracer(tree), bvh_(std::move(bvh)) {}
  // Builds the BVH over `tree`'s leaves (BuildLeafBvh, its arguments and
  // errors).
  static absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> Build(
      const KdTree& tree, uint64_t max_packet_bytes = std::numeric_limits<uint64_t>::max(),
      const std::string& how_to_raise = "KdTreeBvhTracer::Build's max_packet_bytes");
  std::string name() const override { return "kdtree_bvh"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override { return IntersectLeafBvh(bvh_, ray); }
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override {
    return OccludedLeafBvh(bvh_, ray, origin_tri);
  }
  // Packets through the same BVH (leaf_bvh_packet_kernel.cc).
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override {
    IntersectPacketLeafBvh(bvh_, rays, n, hits, closest_counters());
  }
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override {
    OccludedPacketLeafBvh(bvh_, rays, n, origin_tris, occluded, any_counters());
  }
  const LeafBvh& bvh() const { return bvh_; }

 private:
  LeafBvh bvh_;
};

// The leaf-BVH kernels over a BVH of whole triangles, no kd-tree
// (cc/kdtree/triangle_bvh.h: the baseline for what the kd-tree's leaves
// cost): the same answers as KdTreeTracer's; secondary rays that name their
// origin triangle leave it untested.
// Tracers may share one hierarchy (render_bench's count of the packets'
// work traces the timed tracer's).
class TriangleBvhTracer : public Tracer {
 public:
  explicit TriangleBvhTracer(std::shared_ptr<const LeafBvh> bvh) : bvh_(std::move(bvh)) {}
  // Builds the hierarchy over `soup` (BuildTriangleBvh's errors) and its
  // tracer, timing the build (build_seconds).
  static absl::StatusOr<std::unique_ptr<TriangleBvhTracer>> Build(const TriangleSoup& soup);
  std::string name() const override { return "triangle_bvh"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override {
    return IntersectLeafBvh(*bvh_, ray);
  }
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override {
    return OccludedLeafBvh(*bvh_, ray, origin_tri);
  }
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override {
    IntersectPacketLeafBvh(*bvh_, rays, n, hits, closest_);
  }
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override {
    OccludedPacketLeafBvh(*bvh_, rays, n, origin_tris, occluded, any_);
  }
  // As KdTreeTracer::CountPackets (render with one thread).
  void CountPackets(PacketCounters* closest, PacketCounters* any) {
    closest_ = closest;
    any_ = any;
  }
  const std::shared_ptr<const LeafBvh>& bvh() const { return bvh_; }
  double build_seconds() const { return build_seconds_; }  // Build's; 0 otherwise

 private:
  std::shared_ptr<const LeafBvh> bvh_;
  double build_seconds_ = 0;
  PacketCounters* closest_ = nullptr;
  PacketCounters* any_ = nullptr;
};

// Every triangle tested (cc/kdtree/brute_force.h). `bf` must outlive it.
class BruteForceTracer : public Tracer {
 public:
  explicit BruteForceTracer(const BruteForce& bf) : bf_(bf) {}
  std::string name() const override { return "brute_force"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override { return bf_.Intersect(ray); }
  // Tests every triangle, the origin one too.
  bool Occluded(const Ray& ray, uint32_t) const override { return bf_.Occluded(ray); }

 private:
  const BruteForce& bf_;
};

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_KDTREE_TRACER_H_
