// What the builders pass down the recursion: a triangle and the box of the
// part of it that lies in the current node (its tight box, or a clipped box).
//
// Only clipping (and perfect splits) changes a reference's box. Without them
// every reference keeps its triangle's tight box, so the builder passes bare
// triangle indices (IndexRef, 4 bytes instead of BuildRef's 28) and reads the
// boxes from one array indexed by triangle. The two kinds give the same boxes,
// hence the same splits and the same tree; BoxOf and TriOf read either.
#ifndef KDTREE_CC_KDTREE_BUILD_REF_H_
#define KDTREE_CC_KDTREE_BUILD_REF_H_

#include <xmmintrin.h>

#include <cstdint>

#include "cc/geometry/aabb.h"

namespace kdtree {

struct BuildRef {
  AABB box;
  uint32_t tri;
};

// A triangle index: the box is boxes[tri] (see above).
using IndexRef = uint32_t;

inline const AABB& BoxOf(const BuildRef& r, const AABB* /*boxes*/) { return r.box; }
inline const AABB& BoxOf(IndexRef r, const AABB* boxes) { return boxes[r]; }
inline uint32_t TriOf(const BuildRef& r) { return r.tri; }
inline uint32_t TriOf(IndexRef r) { return r; }

// Coordinate `axis` of the boxes of refs[0..3]: their lo corners in *lo and
// their hi corners in *hi, lane i for reference i (the binning and the
// partition of four references at a time).
template <class Ref>
inline void LoadAxis4(const Ref* refs, const AABB* boxes, int axis, __m128* lo, __m128* hi) {
  const float* c0 = Coords(BoxOf(refs[0], boxes)) + axis;
  const float* c1 = Coords(BoxOf(refs[1], boxes)) + axis;
  const float* c2 = Coords(BoxOf(refs[2], boxes)) + axis;
  const float* c3 = Coords(BoxOf(refs[3], boxes)) + axis;
  *lo = _mm_setr_ps(c0[0], c1[0], c2[0], c3[0]);
  *hi = _mm_setr_ps(c0[3], c1[3], c2[3], c3[3]);
}

// A split plane chosen by a strategy; found == false means "make a leaf".
struct Split {
  bool found = false;
  int axis = 0;
  float pos = 0.0f;
  float cost = 0.0f;  // the strategy's cost (binned SAH only)
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BUILD_REF_H_
