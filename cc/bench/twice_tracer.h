// A tracer that answers every query by tracing it twice in a row with another
// tracer (render_bench --twice): the second trace of a ray or packet runs
// right after the first, on the same nodes, triangles and branches, with the
// caches and the branch predictors as the first left them. A render with it
// less a render with the tracer itself, round by round, is the time of the
// second traces alone; the first trace's time over it says how much of a
// tracer's work is first touches (memory and prediction) rather than work
// that stays when they are warm. Both tracers of a comparison get the same
// treatment, so the warm ratio compares their work without those first
// touches.
#ifndef KDTREE_CC_BENCH_TWICE_TRACER_H_
#define KDTREE_CC_BENCH_TWICE_TRACER_H_

#include <cstdint>
#include <string>

#include "cc/geometry/ray.h"
#include "cc/render/tracer.h"

namespace kdtree {
namespace bench {

class TwiceTracer : public Tracer {
 public:
  explicit TwiceTracer(const Tracer* inner) : inner_(inner) {}
  const Tracer& inner() const { return *inner_; }

  std::string name() const override { return inner_->name(); }
  Hit Intersect(const Ray& ray) const override {
    inner_->Intersect(ray);
    return inner_->Intersect(ray);
  }
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override {
    inner_->Occluded(ray, origin_tri);
    return inner_->Occluded(ray, origin_tri);
  }
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override {
    inner_->IntersectPacket(rays, n, hits);
    inner_->IntersectPacket(rays, n, hits);
  }
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override {
    inner_->OccludedPacket(rays, n, origin_tris, occluded);
    inner_->OccludedPacket(rays, n, origin_tris, occluded);
  }

 private:
  const Tracer* inner_;
};

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_TWICE_TRACER_H_
