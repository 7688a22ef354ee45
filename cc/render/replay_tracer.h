// A tracer that answers from a recording, so that a render through it times
// the renderer's own work alone: camera rays, hit points, shadow-ray spawns,
// shading, the passes' loops. render_bench (--replay) times it in the same
// rounds as the real tracers and subtracts it, round by round, to compare the
// tracers by their tracing time only, the ray tracer's own share of a render.
//
// One render through Record() (which asks `inner` and keeps every answer, in
// call order), then every render with the same options after Rewind() gets
// the same answers in the same order. The renderer's calls come in a fixed
// order with one thread (RenderOptions::threads == 1); with more, the order
// varies and the answers would not match their rays. A render that asks for
// more answers than were recorded, or a different kind, gets misses and
// overran() turns true (the image then also differs from the recorded one).
#ifndef KDTREE_CC_RENDER_REPLAY_TRACER_H_
#define KDTREE_CC_RENDER_REPLAY_TRACER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/render/tracer.h"

namespace kdtree {

class ReplayTracer : public Tracer {
 public:
  // `inner` answers while recording; it must outlive this tracer.
  explicit ReplayTracer(const Tracer& inner) : inner_(inner) {}
  std::string name() const override { return "replay"; }

  // Forget the recording; the next calls ask `inner` and are kept.
  void Record();
  // Replay the recording from its first answer.
  void Rewind();
  bool overran() const { return overran_; }
  size_t recorded_hits() const { return hits_.size(); }
  size_t recorded_occlusions() const { return occluded_.size(); }

  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override;
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override;
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override;
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override;

 private:
  // The next recorded answer; past the recording, a miss and overran_.
  Hit NextHit() const;
  bool NextOccluded() const;

  const Tracer& inner_;
  bool recording_ = false;
  // Mutable: the Tracer queries are const. One thread only (above).
  mutable std::vector<Hit> hits_;
  mutable std::vector<uint8_t> occluded_;
  mutable size_t next_hit_ = 0, next_occluded_ = 0;
  mutable bool overran_ = false;
};

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_REPLAY_TRACER_H_
