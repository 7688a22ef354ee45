// Embree 3 as a Tracer: the baseline a kd-tree is compared against.
//
// Wald, Woop, Benthin, Johnson, Ernst, "Embree: a kernel framework for
// efficient CPU ray tracing", ACM TOG 33(4), 2014. Same triangle soup as the
// kd-tree (one RTC_GEOMETRY_TYPE_TRIANGLE geometry, triangle i = vertices 3i,
// 3i+1, 3i+2, so primID is our triangle index), rtcIntersect1 for closest hit
// and rtcOccluded1 for any hit, no filters; default scene flags unless
// EmbreeOptions::robust.
// Hit::u, v are Embree's barycentrics, the same convention as ours (hit point
// = (1 - u - v) a + u b + v c). Embree reports hits with tnear <= t <= tfar.
//
// Build time is the time of rtcCommitScene only (device, scene and buffer
// creation excluded); its memory (bvh_bytes) what Embree's memory monitor
// (rtcSetDeviceMemoryMonitorFunction) counts as held after it and not
// before: the BVH and its leaves, without the vertex and index buffers.
// `threads` is passed to rtcNewDevice ("threads=1" for the single-thread
// comparison), which also bounds Embree's build.
#ifndef KDTREE_CC_EMBREE_EMBREE_TRACER_H_
#define KDTREE_CC_EMBREE_EMBREE_TRACER_H_

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "cc/geometry/triangle.h"
#include "cc/render/tracer.h"

namespace kdtree {

enum class EmbreeQuality { kLow, kMedium, kHigh };

// "low", "medium", "high" (any case) -> quality; InvalidArgument otherwise.
absl::StatusOr<EmbreeQuality> ParseEmbreeQuality(const std::string& name);
const char* EmbreeQualityName(EmbreeQuality q);  // "low", "medium", "high"

struct EmbreeOptions {
  // RTC_BUILD_QUALITY_LOW / MEDIUM (Embree's default) / HIGH (spatial splits).
  EmbreeQuality quality = EmbreeQuality::kMedium;
  // Threads of the Embree device (rtcNewDevice "threads=N").
  int threads = 1;
  // RTC_SCENE_FLAG_ROBUST: "acceleration structures that allow for robust
  // traversal, and [no] optimizations that reduce arithmetic accuracy ...
  // for avoiding artifacts caused by rays shooting through edges of
  // neighboring primitives" (rtcSetSceneFlags(3)): Embree's own setting for
  // the accuracy our watertight test (Woop, Benthin & Wald, JCGT 2(1), 2013)
  // gives; it does not promise watertightness (Embree issue #387 reports
  // misses on shared edges with it).
  bool robust = false;
};

class EmbreeTracer : public Tracer {
 public:
  // Builds the scene. Errors: empty soup, Embree device or build errors.
  static absl::StatusOr<std::unique_ptr<EmbreeTracer>> Create(const TriangleSoup& soup,
                                                              const EmbreeOptions& options);
  ~EmbreeTracer() override;
  EmbreeTracer(const EmbreeTracer&) = delete;
  EmbreeTracer& operator=(const EmbreeTracer&) = delete;

  std::string name() const override { return "embree"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override;
  // Embree tests every triangle: origin_tri is not used.
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override;
  // rtcIntersect16 / rtcOccluded16 on the valid lanes (Embree's packet
  // kernels, or its emulation where the library has no native ray16);
  // IntersectPacket with the coherent flag (the renderer's packets are 4x4
  // camera rays), OccludedPacket without.
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override;
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override;
  // Whether the library traces ray16 packets natively
  // (RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED).
  bool native_ray16() const { return native_ray16_; }

  // Wall time of rtcCommitScene.
  double build_seconds() const { return build_seconds_; }
  // Bytes rtcCommitScene left allocated (its net count by the device's
  // memory monitor): the acceleration structure Embree traverses.
  int64_t bvh_bytes() const { return bvh_bytes_; }

 private:
  EmbreeTracer() = default;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_seconds_ = 0;
  int64_t bvh_bytes_ = 0;
  // What the memory monitor has counted: allocations less frees, from every
  // thread of the device.
  std::atomic<int64_t> monitored_{0};
  bool native_ray16_ = false;
};

}  // namespace kdtree

#endif  // KDTREE_CC_EMBREE_EMBREE_TRACER_H_
