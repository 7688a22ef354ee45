// Highway masks as lane bits and back, for the packet kernel's per-target
// code (ray_packet_kernel.cc, ray_packet_setup.cc). Included once per target
// (Highway's per-target include guard).
#if defined(KDTREE_CC_KDTREE_MASK_BITS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_MASK_BITS_INL_H_
#undef KDTREE_CC_KDTREE_MASK_BITS_INL_H_
#else
#define KDTREE_CC_KDTREE_MASK_BITS_INL_H_
#endif

#include <cstdint>
#include <cstring>

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The mask's lanes as bits (bit i: lane i).
template <class D>
HWY_INLINE uint32_t Bits(D d, hn::Mask<D> m) {
  uint8_t bytes[8] = {0};
  hn::StoreMaskBits(d, m, bytes);
  uint32_t bits;
  std::memcpy(&bits, bytes, sizeof(bits));
  return bits;
}

// The bits of all of D's lanes.
template <class D>
constexpr uint32_t AllLanes() {
  return hn::MaxLanes(D()) >= 32 ? ~0u : (1u << hn::MaxLanes(D())) - 1;
}

// Bits back to a mask.
template <class D>
HWY_INLINE hn::Mask<D> FromBits(D d, uint32_t bits) {
  uint8_t bytes[8] = {0};
  std::memcpy(bytes, &bits, sizeof(bits));
  return hn::LoadMaskBits(d, bytes);
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_MASK_BITS_INL_H_
