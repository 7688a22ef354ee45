// One fuzz case for the traversal: the bytes become a small scene and a few
// rays, every preset is built on the scene, and each ray's closest and any hit
// are compared with brute force in both intersection modes, and through the
// BVH over each tree's leaves (leaf_bvh.h) with the watertight test. Used by the
// libFuzzer target (traversal_fuzzer.cc) and by a deterministic smoke test.
#ifndef KDTREE_CC_ROBUST_TRAVERSAL_FUZZ_H_
#define KDTREE_CC_ROBUST_TRAVERSAL_FUZZ_H_

#include <cstddef>
#include <cstdint>

namespace kdtree {
namespace robust {

// Decoding: byte 0 picks the coordinate alphabet (raw float bits, which may be
// NaN, Inf, denormal or huge; small dyadic values (b - 128) / 8, which make
// axis-aligned, coplanar and touching triangles; or a mix). Then up to 48
// triangles of 9 values, then rays of 6 values (direction values from a set
// with +0, -0, denormals and +-1 in the dyadic alphabet) and a byte that
// sometimes gives the ray a tmin of a dyadic value (-16 to 16) or -0. Triangles with
// non-finite or absurd coordinates are dropped first, as at load.
// Every preset's build gets 64 MB (BuildLimits); a build over it has no tree
// to check. Returns the number of disagreements with brute force (0 when
// correct); never crashes or hangs on any input.
size_t TraversalFuzzCase(const uint8_t* data, size_t size);

}  // namespace robust
}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_TRAVERSAL_FUZZ_H_
