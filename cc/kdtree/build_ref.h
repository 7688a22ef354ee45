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

// A split plane chosen by a strategy; found == false means "make a leaf".
struct Split {
  bool found = false;
  int axis = 0;
  float pos = 0.0f;
  float cost = 0.0f;  // the strategy's cost (binned SAH only)
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BUILD_REF_H_
