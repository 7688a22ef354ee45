// A small lit scene for the renderer tests: a bumpy sphere (radius about 1,
// 1,280 triangles) standing above a ground quad, optionally scaled, and views
// of it with and without a light.
#ifndef KDTREE_CC_RENDER_TEST_SCENE_H_
#define KDTREE_CC_RENDER_TEST_SCENE_H_

#include "cc/geometry/triangle.h"
#include "cc/render/view.h"

namespace kdtree {
namespace testing {

// Sphere around the origin, ground quad y = -1.2, |x|, |z| <= 4; every
// coordinate multiplied by `scale`.
TriangleSoup SphereOnGround(float scale = 1.0f);

// Camera on the +z side, a little above; with_light: one point light above
// and to the left, so that the sphere casts a shadow on the ground.
View SphereView(int width, int height, float scale = 1.0f, bool with_light = true);

}  // namespace testing
}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_TEST_SCENE_H_
