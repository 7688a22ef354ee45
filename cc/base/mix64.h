// SplitMix64's finaliser: a good 64-bit mix of any integer (Steele, Lea and
// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014).
// The one copy shared by the scene generators' seeded randomness
// (cc/scenes/random.h) and the renderer's per-pixel sample hash
// (cc/render/secondary_rays.cc).
#ifndef KDTREE_CC_BASE_MIX64_H_
#define KDTREE_CC_BASE_MIX64_H_

#include <cstdint>

namespace kdtree {

inline uint64_t Mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_MIX64_H_
