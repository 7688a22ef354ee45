#include "cc/kdtree/brute_force.h"

#include <cmath>
#include <cstdint>

#include "cc/geometry/ray_check.h"
#include "cc/geometry/watertight.h"

namespace kdtree {

namespace {

// Every index 0 .. n-1, iterable like a candidate list.
struct AllIndices {
  uint32_t n;
  struct It {
    uint32_t i;
    uint32_t operator*() const { return i; }
    It& operator++() {
      ++i;
      return *this;
    }
    bool operator!=(const It& o) const { return i != o.i; }
  };
  It begin() const { return {0}; }
  It end() const { return {n}; }
};

}  // namespace

BruteForce::BruteForce(const TriangleSoup& soup) : verts_(soup.v) {
  tris_.reserve(soup.size());
  for (size_t i = 0; i < soup.size(); ++i) {
    tris_.push_back(MakeTriAccel(soup.a(i), soup.b(i), soup.c(i)));
  }
}

template <IntersectionMode kMode, bool kAnyHit, typename Indices>
Hit BruteForce::Run(const Ray& input, const Indices& indices) const {
  Hit best;
  Ray ray = input;
  if (!SanitizeRay(&ray)) return best;
  WatertightRay wray{};
  if (kMode == IntersectionMode::kWatertight) wray = MakeWatertightRay(ray);
  best.t = ray.tmax;
  for (const uint32_t tri : indices) {
    float t, u, v;
    bool hit;
    if (kMode == IntersectionMode::kWatertight) {
      const Vec3* p = &verts_[3 * static_cast<size_t>(tri)];
      hit = IntersectTriangleWatertight(wray, p[0], p[1], p[2], ray.tmin, best.t, &t, &u, &v);
    } else {
      hit = IntersectTriangle(ray, tris_[tri], ray.tmin, best.t, &t, &u, &v);
    }
    if (hit && Closer(t, tri, best)) {
      best.tri = tri;
      best.t = t;
      best.u = u;
      best.v = v;
      if (kAnyHit) break;
    }
  }
  if (!best.hit()) best.t = INFINITY;
  return best;
}

Hit BruteForce::Intersect(const Ray& ray, IntersectionMode mode) const {
  const AllIndices all{static_cast<uint32_t>(tris_.size())};
  return mode == IntersectionMode::kWatertight
             ? Run<IntersectionMode::kWatertight, false>(ray, all)
             : Run<IntersectionMode::kFast, false>(ray, all);
}

Hit BruteForce::Intersect(const Ray& ray, const std::vector<uint32_t>& candidates,
                          IntersectionMode mode) const {
  return mode == IntersectionMode::kWatertight
             ? Run<IntersectionMode::kWatertight, false>(ray, candidates)
             : Run<IntersectionMode::kFast, false>(ray, candidates);
}

bool BruteForce::Occluded(const Ray& ray, IntersectionMode mode) const {
  const AllIndices all{static_cast<uint32_t>(tris_.size())};
  return (mode == IntersectionMode::kWatertight
              ? Run<IntersectionMode::kWatertight, true>(ray, all)
              : Run<IntersectionMode::kFast, true>(ray, all))
      .hit();
}

}  // namespace kdtree
