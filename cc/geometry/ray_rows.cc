// RayRows (ray_rows.h) for every x86 target Highway knows, chosen at run
// time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cc/geometry/ray_rows.cc"
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// Per target, after foreach_target.h:
#include "cc/geometry/ray_rows-inl.h"

#include <cstdint>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/ray_rows.h"
#include "hwy/targets.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace HWY_NAMESPACE {

void RayRowsImpl(const Ray* rays, int n, float* const rows[8]) {
  static_assert(sizeof(Ray) == 8 * sizeof(float), "a ray is 8 floats");
  const float* flat = reinterpret_cast<const float*>(rays);
  const hn::ScalableTag<float> d;
  for (size_t base = 0; base < 16; base += hn::Lanes(d)) {
    hn::Vec<decltype(d)> c[8];
    LoadRayRows(d, flat, n, base, c);
    for (int k = 0; k < 8; ++k) hn::Store(c[k], d, rows[k] + base);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace kdtree {

HWY_EXPORT(RayRowsImpl);

void RayRows(const Ray* rays, int n, float* const rows[8]) {
  HWY_DYNAMIC_DISPATCH(RayRowsImpl)(rays, n, rows);
}

std::vector<int64_t> RayRowsTargets() { return hwy::SupportedAndGeneratedTargets(); }

}  // namespace kdtree
#endif  // HWY_ONCE
