#include "cc/render/secondary_rays.h"

#include <cmath>

#include "cc/base/mix64.h"

namespace kdtree {
namespace {

// Orthonormal basis around unit n: Duff et al., "Building an orthonormal
// basis, revisited", JCGT 6(1), 2017.
void Basis(const Vec3& n, Vec3* b1, Vec3* b2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  *b1 = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  *b2 = Vec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace

SurfacePoint MakeSurfacePoint(const TriangleSoup& soup, const Ray& ray, const Hit& hit) {
  const Vec3& a = soup.a(hit.tri);
  const Vec3& b = soup.b(hit.tri);
  const Vec3& c = soup.c(hit.tri);
  SurfacePoint sp;
  sp.point = HitPointWithError(a, b, c, hit.u, hit.v);
  Vec3 n = GeometricNormal(a, b, c);
  if (Dot(n, ray.dir) > 0.0f) n = -n;
  sp.normal = n;
  return sp;
}

Ray ShadowRay(const SurfacePoint& sp, const Vec3& light) {
  return SpawnShadowRay(sp.point, sp.normal, light);
}

void HashUniforms(uint32_t pixel, uint32_t sample, float* r1, float* r2) {
  const uint64_t z = Mix64(static_cast<uint64_t>(pixel) << 32 | sample);
  *r1 = static_cast<float>(z >> 40) * (1.0f / 16777216.0f);
  *r2 = static_cast<float>((z >> 8) & 0xffffff) * (1.0f / 16777216.0f);
}

Ray AoRay(const SurfacePoint& sp, uint32_t pixel, int sample, float distance) {
  float r1, r2;
  HashUniforms(pixel, static_cast<uint32_t>(sample), &r1, &r2);
  const float phi = 6.28318530717958647f * r1;
  const float r = std::sqrt(r2);
  const float z = std::sqrt(std::fmax(0.0f, 1.0f - r2));
  Vec3 b1, b2;
  Basis(sp.normal, &b1, &b2);
  const Vec3 dir = Normalize(b1 * (r * std::cos(phi)) + b2 * (r * std::sin(phi)) + sp.normal * z);
  Ray ray = SpawnRay(sp.point, sp.normal, dir);
  ray.tmin = 0.0f;
  ray.tmax = distance;
  return ray;
}

}  // namespace kdtree
