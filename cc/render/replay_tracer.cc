#include "cc/render/replay_tracer.h"

namespace kdtree {

void ReplayTracer::Record() {
  recording_ = true;
  hits_.clear();
  occluded_.clear();
  next_hit_ = next_occluded_ = 0;
  overran_ = false;
}

void ReplayTracer::Rewind() {
  recording_ = false;
  next_hit_ = next_occluded_ = 0;
  overran_ = false;
}

Hit ReplayTracer::NextHit() const {
  if (next_hit_ < hits_.size()) return hits_[next_hit_++];
  overran_ = true;
  return Hit();
}

bool ReplayTracer::NextOccluded() const {
  if (next_occluded_ < occluded_.size()) return occluded_[next_occluded_++] != 0;
  overran_ = true;
  return false;
}

Hit ReplayTracer::Intersect(const Ray& ray) const {
  if (recording_) {
    hits_.push_back(inner_.Intersect(ray));
    return hits_.back();
  }
  return NextHit();
}

bool ReplayTracer::Occluded(const Ray& ray, uint32_t origin_tri) const {
  if (recording_) {
    occluded_.push_back(inner_.Occluded(ray, origin_tri));
    return occluded_.back() != 0;
  }
  return NextOccluded();
}

void ReplayTracer::IntersectPacket(const Ray* rays, int n, Hit* hits) const {
  if (recording_) {
    inner_.IntersectPacket(rays, n, hits);
    hits_.insert(hits_.end(), hits, hits + n);
    return;
  }
  for (int i = 0; i < n; ++i) hits[i] = NextHit();
}

void ReplayTracer::OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                                  bool* occluded) const {
  if (recording_) {
    inner_.OccludedPacket(rays, n, origin_tris, occluded);
    occluded_.insert(occluded_.end(), occluded, occluded + n);
    return;
  }
  for (int i = 0; i < n; ++i) occluded[i] = NextOccluded();
}

}  // namespace kdtree
