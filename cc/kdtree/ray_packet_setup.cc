// The packet traversal's per-ray set-up: SanitizeRay (ray_check.h) and
// SetUpRay's vector path (ray_setup.h) for a packet's 16 lanes at once,
// compiled for every x86 target Highway knows and chosen at run time like
// the kernel (ray_packet_kernel.cc). Bit for bit the scalar set-up:
// ray_setup_test.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cc/kdtree/ray_packet_setup.cc"
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// Per target, after foreach_target.h:
#include "cc/geometry/ray_rows-inl.h"
#include "cc/kdtree/mask_bits-inl.h"

#include <cstddef>
#include <cstdint>
#include <limits>

#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_setup.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A chunk's rays as the box's set-up leaves them for the frames' (kept in
// registers between SetUpBoxChunk and SetUpFrameChunk).
template <class D>
struct ChunkRays {
  hn::Vec<D> o[3], dir[3], depth[3], inv[3];
};

// SetUpRay's vector path (ray_setup.h) for the lanes [base, base + Lanes(d)),
// operation for operation (MINPS / MAXPS operand order included), up to the
// box: reciprocals, tolerances and the interval in the box, with *r for the
// frames; returns the lanes that reach the box.
template <class D>
HWY_INLINE uint32_t SetUpBoxChunk(D d, const AABB& box, size_t base, PacketRays* p,
                                  ChunkRays<D>* r) {
  using V = hn::Vec<D>;
  const V one = hn::Set(d, 1.0f), pad = hn::Set(d, ray_setup::kPad);
  V dl[3], dh[3];
  V reach = hn::Zero(d);
  for (int k = 0; k < 3; ++k) {
    r->o[k] = hn::Load(d, p->org[k] + base);
    r->dir[k] = hn::Load(d, p->dir[k] + base);
    dl[k] = hn::Sub(hn::Set(d, box.lo[k]), r->o[k]);
    dh[k] = hn::Sub(hn::Set(d, box.hi[k]), r->o[k]);
    r->inv[k] = hn::Div(one, r->dir[k]);
    hn::Store(r->inv[k], d, p->inv[k] + base);
    // reach = Max(reach, Max(|dl|, |dh|)), Max(a, b) = a > b ? a : b.
    r->depth[k] = hn::Max(hn::Abs(dl[k]), hn::Abs(dh[k]));
    reach = hn::Max(reach, r->depth[k]);
  }
  const V delta = hn::Mul(hn::Set(d, ray_setup::kSpatialTol), reach);
  hn::Store(delta, d, p->delta + base);
  V lo = hn::Load(d, p->tmin + base), hi = hn::Load(d, p->tmax + base);
  for (int k = 0; k < 3; ++k) {
    const V tol = hn::Mul(delta, hn::Abs(r->inv[k]));
    hn::Store(tol, d, p->tol[k] + base);
    const V tn = hn::Mul(dl[k], r->inv[k]), tf = hn::Mul(dh[k], r->inv[k]);
    V t0 = hn::Min(tf, tn), t1 = hn::Max(tn, tf);
    t0 = hn::Sub(t0, hn::Add(hn::Mul(hn::Abs(t0), pad), tol));
    t1 = hn::Add(t1, hn::Add(hn::Mul(hn::Abs(t1), pad), tol));
    lo = hn::Max(t0, lo);
    hi = hn::Min(t1, hi);
  }
  hn::Store(lo, d, p->t_entry + base);
  hn::Store(hi, d, p->t_exit + base);
  return Bits(d, hn::Le(lo, hi));
}

// The rest of SetUpRay for the same lanes, from SetUpBoxChunk's `r`: its
// watertight axes and shears (MakeWatertightRay), hit slack and keys.
template <class D>
HWY_INLINE void SetUpFrameChunk(D d, size_t base, const ChunkRays<D>& r, PacketRays* p) {
  using V = hn::Vec<D>;
  const V(&o)[3] = r.o;
  const V(&dir)[3] = r.dir;
  const V(&depth)[3] = r.depth;
  const V(&inv)[3] = r.inv;
  // WatertightAxes: kz the largest |d| (ties to the lower axis), kx and ky
  // the next two cyclically, swapped when d[kz] < 0.
  const V ax = hn::Abs(dir[0]), ay = hn::Abs(dir[1]), az = hn::Abs(dir[2]);
  const auto on_x = hn::And(hn::Ge(ax, ay), hn::Ge(ax, az));
  const auto on_y = hn::AndNot(hn::Ge(ax, ay), hn::Ge(ay, az));
  const auto pick = [&](const V v[3], int kx_of_x, int kx_of_y, int kx_of_z) {
    return hn::IfThenElse(on_x, v[kx_of_x], hn::IfThenElse(on_y, v[kx_of_y], v[kx_of_z]));
  };
  const V den = pick(dir, 0, 1, 2);
  const auto flip = hn::Lt(den, hn::Zero(d));
  const V dx0 = pick(dir, 1, 2, 0), dy0 = pick(dir, 2, 0, 1);
  const V ox0 = pick(o, 1, 2, 0), oy0 = pick(o, 2, 0, 1);
  const V sx = hn::Div(hn::IfThenElse(flip, dy0, dx0), den);
  const V sy = hn::Div(hn::IfThenElse(flip, dx0, dy0), den);
  hn::Store(sx, d, p->sx + base);
  hn::Store(sy, d, p->sy + base);
  hn::Store(pick(inv, 0, 1, 2), d, p->sz + base);  // 1 / den: inv's quotient, not a second
  hn::Store(hn::IfThenElse(flip, oy0, ox0), d, p->ox + base);
  hn::Store(hn::IfThenElse(flip, ox0, oy0), d, p->oy + base);
  hn::Store(pick(o, 0, 1, 2), d, p->oz + base);
  const V depth_kz = pick(depth, 0, 1, 2);
  hn::Store(hn::Mul(hn::Set(d, ray_setup::kHitSlack), hn::Div(depth_kz, hn::Abs(den))), d,
            p->slack + base);
  // ShearWeight: FMax(|s|, m) = |s| > m ? |s| : m for each shear.
  const V min_shear = hn::Set(d, watertight_internal::kEdgeBoundMinShear);
  hn::Store(hn::Add(hn::Max(hn::Abs(sx), min_shear), hn::Max(hn::Abs(sy), min_shear)), d,
            p->shear_weight + base);
  // The keys: sign bits of the direction, and kz (1 on_y, 2 neither).
  const hn::RebindToSigned<D> di;
  const auto zero_i = hn::Zero(di);
  for (int k = 0; k < 3; ++k) {
    p->key_bits[k] |= Bits(di, hn::Lt(hn::BitCast(di, dir[k]), zero_i)) << base;
  }
  p->key_bits[3] |= Bits(d, on_y) << base;
  p->key_bits[4] |= Bits(d, hn::Not(hn::Or(on_x, on_y))) << base;
}

// SanitizeRay (ray_check.h) for the lanes [base, base + Lanes(d)) of rays
// [0, n) (8 floats each: origin, dir, tmin, tmax), in vectors: stores their
// components into p, directions sanitized (a component below the smallest
// normal float becomes a zero of its sign); returns the lanes with a valid
// ray (none from n on: those lanes hold zeros) and
// sets *zero to those with a zero direction component and *behind to those
// with tmin >= 0.
template <class D>
HWY_INLINE uint32_t LoadChunk(D d, const float* rays, int n, size_t base, PacketRays* p,
                              uint32_t* zero, uint32_t* behind) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const auto lane = hn::Iota(di, static_cast<int32_t>(base));
  const auto in = hn::Lt(lane, hn::Set(di, n));
  V c[8];
  kdtree::HWY_NAMESPACE::LoadRayRows(d, rays, n, base, c);
  const V tmin = c[6], tmax = c[7];
  auto valid = hn::And(hn::Le(tmin, tmax), hn::RebindMask(d, in));  // also false for NaN
  auto nonzero = hn::Lt(tmin, hn::Zero(d));  // all false
  auto has_zero = nonzero;
  const V min_normal = hn::Set(d, std::numeric_limits<float>::min());
  for (int k = 0; k < 3; ++k) {
    const V o = c[k];
    V dir = c[3 + k];
    valid = hn::And(valid, hn::And(hn::IsFinite(o), hn::IsFinite(dir)));
    dir = hn::IfThenElse(hn::Lt(hn::Abs(dir), min_normal), hn::CopySign(hn::Zero(d), dir), dir);
    const auto is_zero = hn::Eq(dir, hn::Zero(d));
    nonzero = hn::Or(nonzero, hn::Not(is_zero));
    has_zero = hn::Or(has_zero, is_zero);
    hn::Store(o, d, p->org[k] + base);
    hn::Store(dir, d, p->dir[k] + base);
  }
  hn::Store(tmin, d, p->tmin + base);
  hn::Store(tmax, d, p->tmax + base);
  valid = hn::And(valid, nonzero);
  *zero |= Bits(d, hn::And(valid, has_zero)) << base;
  *behind |= Bits(d, hn::And(valid, hn::Ge(tmin, hn::Zero(d)))) << base;
  return Bits(d, valid) << base;
}

// Lanes outside `plain` get lane c's components (so that their arithmetic
// stays finite).
template <class D>
HWY_INLINE void CopyChunk(D d, size_t base, uint32_t plain, int c, PacketRays* p) {
  const auto keep = FromBits(d, plain >> base);
  float* const rows[8] = {p->org[0], p->org[1], p->org[2], p->dir[0],
                          p->dir[1], p->dir[2], p->tmin,   p->tmax};
  for (float* row : rows) {
    hn::Store(hn::IfThenElse(keep, hn::Load(d, row + base), hn::Set(d, row[c])), d, row + base);
  }
}

uint32_t LoadLanesImpl(const Ray* rays, int n, PacketRays* p, uint32_t* zero) {
  static_assert(sizeof(Ray) == 8 * sizeof(float), "a ray is 8 floats");
  const float* flat = reinterpret_cast<const float*>(rays);
  const hn::ScalableTag<float> d;
  const size_t w = hn::Lanes(d);
  uint32_t valid = 0;
  *zero = 0;
  p->behind = 0;
  for (size_t base = 0; base < kLanes; base += w) {
    valid |= LoadChunk(d, flat, n, base, p, zero, &p->behind);
  }
  const uint32_t plain = valid & ~*zero;
  if (valid != 0 && plain != kAllLanes) {
    const int c = __builtin_ctz(plain != 0 ? plain : valid);
    for (size_t base = 0; base < kLanes; base += w) CopyChunk(d, base, plain, c, p);
  }
  return valid;
}

uint32_t SetUpLanesImpl(const AABB& box, PacketRays* p, bool frames_if_none) {
  const hn::ScalableTag<float> d;
  const size_t n = hn::Lanes(d);
  uint32_t live = 0;
  for (uint32_t& bits : p->key_bits) bits = 0;
  ChunkRays<hn::ScalableTag<float>> r[kLanes / hn::MaxLanes(d)];
  for (size_t base = 0; base < kLanes; base += n) {
    live |= SetUpBoxChunk(d, box, base, p, &r[base / n]) << base;
  }
  // No lane reaches the box (most camera packets: their rays pass the scene
  // by): the frames are not needed (packet_rays.h).
  if (live == 0 && !frames_if_none) return 0;
  for (size_t base = 0; base < kLanes; base += n) SetUpFrameChunk(d, base, r[base / n], p);
  return live;
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace kdtree {
namespace packet_internal {

HWY_EXPORT(SetUpLanesImpl);
HWY_EXPORT(LoadLanesImpl);

uint32_t LoadLanes(const Ray* rays, int n, PacketRays* p, uint32_t* zero) {
  return HWY_DYNAMIC_DISPATCH(LoadLanesImpl)(rays, n, p, zero);
}

uint32_t SetUpLanes(const AABB& box, PacketRays* p, bool frames_if_none) {
  return HWY_DYNAMIC_DISPATCH(SetUpLanesImpl)(box, p, frames_if_none);
}

}  // namespace packet_internal
}  // namespace kdtree
#endif  // HWY_ONCE
