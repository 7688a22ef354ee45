#include "cc/kdtree/brute_force.h"

#include <cmath>
#include <cstdint>

namespace kdtree {

BruteForce::BruteForce(const TriangleSoup& soup) {
  tris_.reserve(soup.size());
  for (size_t i = 0; i < soup.size(); ++i) tris_.push_back(MakeTriAccel(soup.a(i), soup.b(i), soup.c(i)));
}

Hit BruteForce::Intersect(const Ray& ray) const {
  Hit best;
  best.t = ray.tmax;
  for (size_t i = 0; i < tris_.size(); ++i) {
    float t, u, v;
    const uint32_t tri = static_cast<uint32_t>(i);
    if (IntersectTriangle(ray, tris_[i], ray.tmin, best.t, &t, &u, &v) && Closer(t, tri, best)) {
      best.tri = tri;
      best.t = t;
      best.u = u;
      best.v = v;
    }
  }
  if (!best.hit()) best.t = INFINITY;
  return best;
}

Hit BruteForce::Intersect(const Ray& ray, const std::vector<uint32_t>& candidates) const {
  Hit best;
  best.t = ray.tmax;
  for (const uint32_t tri : candidates) {
    float t, u, v;
    if (IntersectTriangle(ray, tris_[tri], ray.tmin, best.t, &t, &u, &v) && Closer(t, tri, best)) {
      best.tri = tri;
      best.t = t;
      best.u = u;
      best.v = v;
    }
  }
  if (!best.hit()) best.t = INFINITY;
  return best;
}

bool BruteForce::Occluded(const Ray& ray) const {
  for (const TriAccel& tri : tris_) {
    float t, u, v;
    if (IntersectTriangle(ray, tri, ray.tmin, ray.tmax, &t, &u, &v)) return true;
  }
  return false;
}

}  // namespace kdtree
