#include "cc/embree/embree_tracer.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace kdtree {
namespace {

// Device errors are collected here (the callback has no other way out).
void OnError(void* user, RTCError code, const char* str) {
  std::string* last = static_cast<std::string*>(user);
  if (last->empty()) *last = absl::StrCat("Embree error ", static_cast<int>(code), ": ", str ? str : "");
}

RTCBuildQuality ToRtc(EmbreeQuality q) {
  switch (q) {
    case EmbreeQuality::kLow: return RTC_BUILD_QUALITY_LOW;
    case EmbreeQuality::kMedium: return RTC_BUILD_QUALITY_MEDIUM;
    case EmbreeQuality::kHigh: return RTC_BUILD_QUALITY_HIGH;
  }
  return RTC_BUILD_QUALITY_MEDIUM;
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
  t->native_ray16_ =
      rtcGetDeviceProperty(t->device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;

  t->scene_ = rtcNewScene(t->device_);
  rtcSetSceneBuildQuality(t->scene_, ToRtc(options.quality));
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

  const auto start = std::chrono::steady_clock::now();
  rtcCommitScene(t->scene_);
  t->build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.time = 0.0f;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
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
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.tnear = ray.tmin;
  r.dir_x = ray.dir.x;
  r.dir_y = ray.dir.y;
  r.dir_z = ray.dir.z;
  r.time = 0.0f;
  r.tfar = ray.tmax;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

namespace {

// The rays of lanes i < n in a packet of 16; `valid` -1 for them, 0 for the
// rest.
void FillRay16(const Ray* rays, int n, int* valid, RTCRay16* r) {
  for (int i = 0; i < 16; ++i) {
    const Ray ray = i < n ? rays[i] : Ray{{0, 0, 0}, {1, 0, 0}};
    valid[i] = i < n ? -1 : 0;
    r->org_x[i] = ray.origin.x;
    r->org_y[i] = ray.origin.y;
    r->org_z[i] = ray.origin.z;
    r->tnear[i] = ray.tmin;
    r->dir_x[i] = ray.dir.x;
    r->dir_y[i] = ray.dir.y;
    r->dir_z[i] = ray.dir.z;
    r->time[i] = 0.0f;
    r->tfar[i] = ray.tmax;
    r->mask[i] = 0xffffffffu;
    r->id[i] = i;
    r->flags[i] = 0;
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
