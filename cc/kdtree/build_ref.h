// What the builders pass down the recursion: a triangle and the box of the
// part of it that lies in the current node (its tight box, or a clipped box).
#ifndef KDTREE_CC_KDTREE_BUILD_REF_H_
#define KDTREE_CC_KDTREE_BUILD_REF_H_

#include <cstdint>

#include "cc/geometry/aabb.h"

namespace kdtree {

struct BuildRef {
  AABB box;
  uint32_t tri;
};

// A split plane chosen by a strategy; found == false means "make a leaf".
struct Split {
  bool found = false;
  int axis = 0;
  float pos = 0.0f;
  float cost = 0.0f;  // the strategy's cost (binned SAH only)
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BUILD_REF_H_
