#include "cc/render/kdtree_tracer.h"

#include "cc/kdtree/traversal.h"

namespace kdtree {

Hit KdTreeTracer::Intersect(const Ray& ray) const {
  return ::kdtree::Intersect(tree_, ray, options_);
}

bool KdTreeTracer::Occluded(const Ray& ray) const {
  return ::kdtree::Occluded(tree_, ray, options_);
}

}  // namespace kdtree
