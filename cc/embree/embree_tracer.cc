#include "cc/embree/embree_tracer.h"

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <immintrin.h>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "cc/geometry/ray_rows.h"

namespace kdtree {
namespace {

// Device errors are collected here (the callback has no other way out).
void OnError(void* user, RTCError code, const char* str) {
  std::string* last = static_cast<std::string*>(user);
  if (last->empty()) *last = absl::StrCat("Embree error ", static_cast<int>(code), ": ", str ? str : "");
}

// The device's memory monitor: bytes allocated (> 0) or freed (< 0), each
// block once (before an allocation, after a free); never refuses one.
bool OnMemory(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<int64_t>*>(user)->fetch_add(static_cast<int64_t>(bytes),
                                                      std::memory_order_relaxed);
  return true;
}

RTCBuildQuality ToRtc(EmbreeQuality q) {
  switch (q) {
    case EmbreeQuality::kLow: return RTC_BUILD_QUALITY_LOW;
    case EmbreeQuality::kMedium: return RTC_BUILD_QUALITY_MEDIUM;
    case EmbreeQuality::kHigh: return RTC_BUILD_QUALITY_HIGH;
  }
  return RTC_BUILD_QUALITY_MEDIUM;
}

// The ray into Embree's single-ray layout (tnear after the origin, time
// after the direction), each half in one 16-byte store: Embree reads the
// halves as 16-byte vectors, which narrower stores would not forward to (a
// stall on every ray; ray.h LoadRay says the same of our side). Not tfar.
void PutRay(const Ray& in, RTCRay* r) {
  const Ray ray = LoadRay(in);
  static_assert(offsetof(RTCRay, tnear) == offsetof(RTCRay, org_x) + 12, "org, tnear");
  static_assert(offsetof(RTCRay, time) == offsetof(RTCRay, dir_x) + 12, "dir, time");
  _mm_storeu_ps(&r->org_x, _mm_setr_ps(ray.origin.x, ray.origin.y, ray.origin.z, ray.tmin));
  _mm_storeu_ps(&r->dir_x, _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 0.0f));
  r->tfar = ray.tmax;
  r->mask = 0xffffffffu;
  r->id = 0;
  r->flags = 0;
}

}  // namespace

absl::StatusOr<EmbreeQuality> ParseEmbreeQuality(const std::string& name) {
  const std::string n = absl::AsciiStrToLower(name);
  if (n == "low") return EmbreeQuality::kLow;
  if (n == "medium") return EmbreeQuality::kMedium;
  if (n == "high") return EmbreeQuality::kHigh;
  return absl::InvalidArgumentError(
      absl::StrCat("unknown Embree build quality '", name, "' (low, medium or high)"));
}

const char* EmbreeQualityName(EmbreeQuality q) {
  switch (q) {
    case EmbreeQuality::kLow: return "low";
    case EmbreeQuality::kMedium: return "medium";
    case EmbreeQuality::kHigh: return "high";
  }
  return "medium";
}

absl::StatusOr<std::unique_ptr<EmbreeTracer>> EmbreeTracer::Create(const TriangleSoup& soup,
                                                                   const EmbreeOptions& options) {
  if (soup.empty()) return absl::InvalidArgumentError("Embree: no triangles");
  if (soup.size() > std::numeric_limits<uint32_t>::max() / 3) {
    return absl::InvalidArgumentError("Embree: too many triangles");
  }
  std::unique_ptr<EmbreeTracer> t(new EmbreeTracer());
  const std::string config = absl::StrCat("threads=", options.threads < 1 ? 1 : options.threads);
  t->device_ = rtcNewDevice(config.c_str());
  if (t->device_ == nullptr) {
    return absl::InternalError(absl::StrCat("Embree: rtcNewDevice(\"", config, "\") failed: error ",
                                            static_cast<int>(rtcGetDeviceError(nullptr))));
  }
  std::string error;
  rtcSetDeviceErrorFunction(t->device_, OnError, &error);
  rtcSetDeviceMemoryMonitorFunction(t->device_, OnMemory, &t->monitored_);
  t->native_ray16_ =
      rtcGetDeviceProperty(t->device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;

  t->scene_ = rtcNewScene(t->device_);
  rtcSetSceneBuildQuality(t->scene_, ToRtc(options.quality));
  if (options.robust) rtcSetSceneFlags(t->scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(t->device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geom, ToRtc(options.quality));
  const size_t n = soup.size();
  float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  uint32_t* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), n));
  if (vb == nullptr || ib == nullptr) {
    rtcReleaseGeometry(geom);
    return absl::ResourceExhaustedError(absl::StrCat("Embree: cannot allocate buffers: ", error));
  }
  for (size_t i = 0; i < 3 * n; ++i) {
    vb[3 * i] = soup.v[i].x;
    vb[3 * i + 1] = soup.v[i].y;
    vb[3 * i + 2] = soup.v[i].z;
    ib[i] = static_cast<uint32_t>(i);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(t->scene_, geom);
  rtcReleaseGeometry(geom);

  const int64_t before = t->monitored_.load();
  const auto start = std::chrono::steady_clock::now();
  rtcCommitScene(t->scene_);
  t->build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t->bvh_bytes_ = t->monitored_.load() - before;
  rtcSetDeviceErrorFunction(t->device_, nullptr, nullptr);
  if (!error.empty()) return absl::InternalError(error);
  return t;
}

EmbreeTracer::~EmbreeTracer() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

Hit EmbreeTracer::Intersect(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  PutRay(ray, &rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  Hit hit;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    hit.tri = rh.hit.primID;
    hit.t = rh.ray.tfar;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
  }
  return hit;
}

bool EmbreeTracer::Occluded(const Ray& ray, uint32_t /*origin_tri*/) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  PutRay(ray, &r);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

namespace {

// The rows of a packet of 16 that are not the rays' own (time, mask, id,
// flags), `valid` (-1 for lanes i < n, 0 for the rest) and direction
// (1, 0, 0) in the lanes from n on (invalid for Embree; RayRows left their
// rows 0), each row in one 64-byte store: Embree's 16-wide kernel loads a row
// as one vector, which narrower stores would not forward to (ray.h
// LoadRay). The whole fill so, against a scalar loop over the lanes for
// every row (paired rounds, render_bench, bunny, city, hairball-small):
// Embree's packets 1.5-3.5 % faster.
__attribute__((target("avx512f"))) void FillFixedRows16Wide(int n, int* valid, RTCRay16* r) {
  const __mmask16 live = static_cast<__mmask16>((1u << n) - 1);
  _mm512_store_ps(r->dir_x, _mm512_mask_mov_ps(_mm512_set1_ps(1.0f), live,
                                               _mm512_load_ps(r->dir_x)));
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  _mm512_store_ps(r->time, _mm512_setzero_ps());
  _mm512_store_si512(r->mask, _mm512_set1_epi32(-1));
  _mm512_store_si512(r->id, lane);
  _mm512_store_si512(r->flags, _mm512_setzero_si512());
  _mm512_store_si512(valid, _mm512_maskz_set1_epi32(live, -1));
}

// FillFixedRows16Wide's rows a lane at a time, on CPUs without AVX-512 (where
// Embree's kernels are narrower).
void FillFixedRows16(int n, int* valid, RTCRay16* r) {
  for (int i = 0; i < 16; ++i) {
    if (i >= n) r->dir_x[i] = 1.0f;
    r->time[i] = 0.0f;
    r->mask[i] = 0xffffffffu;
    r->id[i] = static_cast<unsigned>(i);
    r->flags[i] = 0;
    valid[i] = i < n ? -1 : 0;
  }
}

// The rays of lanes i < n in a packet of 16 as Embree's RTCRay16. Their rows
// come from RayRows, the kd-tree's packet set-up's own load (ray_rows-inl.h
// LoadRayRows: wide loads and permutes on 16-lane targets, gathers
// elsewhere), so that both tracers pay the same for taking the renderer's
// rays.
void FillRay16(const Ray* rays, int n, int* valid, RTCRay16* r) {
  float* const rows[8] = {r->org_x, r->org_y, r->org_z, r->dir_x,
                          r->dir_y, r->dir_z, r->tnear, r->tfar};
  RayRows(rays, n, rows);
  static const bool wide = __builtin_cpu_supports("avx512f");
  if (wide) {
    FillFixedRows16Wide(n, valid, r);
  } else {
    FillFixedRows16(n, valid, r);
  }
}

}  // namespace

void EmbreeTracer::IntersectPacket(const Ray* rays, int n, Hit* hits) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  // The renderer's packets are 4x4 neighbouring camera rays: tell Embree
  // (its coherent hybrid traversal), the fair bar for our packets (#23).
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[16];
  alignas(64) RTCRayHit16 rh;
  FillRay16(rays, n, valid, &rh.ray);
  for (int i = 0; i < 16; ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, scene_, &ctx, &rh);
  for (int i = 0; i < n; ++i) {
    hits[i] = Hit();
    if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
      hits[i].tri = rh.hit.primID[i];
      hits[i].t = rh.ray.tfar[i];
      hits[i].u = rh.hit.u[i];
      hits[i].v = rh.hit.v[i];
    }
  }
}

void EmbreeTracer::OccludedPacket(const Ray* rays, int n, const uint32_t* /*origin_tris*/,
                                  bool* occluded) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) int valid[16];
  alignas(64) RTCRay16 r;
  FillRay16(rays, n, valid, &r);
  rtcOccluded16(valid, scene_, &ctx, &r);
  for (int i = 0; i < n; ++i) occluded[i] = r.tfar[i] == -std::numeric_limits<float>::infinity();
}

}  // namespace kdtree
