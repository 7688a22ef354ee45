// Deterministic scenes and rays for the kd-tree tests.
#ifndef KDTREE_CC_KDTREE_TEST_SCENES_H_
#define KDTREE_CC_KDTREE_TEST_SCENES_H_

#include <cstdint>
#include <string>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"

namespace kdtree {
namespace testing {

// A closed, bumpy sphere: an icosahedron subdivided `levels` times (20 * 4^levels
// triangles) with seeded radial noise.
TriangleSoup BumpySphere(int levels, uint32_t seed);

// Unit cubes on an integer grid (voxel-world style): every exposed face as two
// triangles lying exactly in integer planes, which are also split planes.
TriangleSoup VoxelGrid(int nx, int ny, int nz, uint32_t seed);

// Random soup of thin slivers (up to 0.17 long, 0.004 wide) in the unit cube.
TriangleSoup ThinSoup(int count, uint32_t seed);

// All triangles in the plane z = 0 (a flat scene: the root box has no depth).
TriangleSoup FlatScene(int count, uint32_t seed);

// Random rays: half aimed at random points of random triangles, half with
// random origins and directions, from around the scene's box.
std::vector<Ray> RandomRays(const TriangleSoup& soup, int count, uint32_t seed);

// Every primary ray of a pinhole camera (width x height) on the +z side of the
// scene box looking at its centre, 45 degree field of view.
std::vector<Ray> CameraRays(const TriangleSoup& soup, int width, int height);

// The four generated scenes the BVH tests trace, by name: "sphere"
// (BumpySphere, 5,120 triangles), "voxels" (VoxelGrid 10 x 6 x 10), "thin"
// (ThinSoup, 2,000) and "flat" (FlatScene, 1,000); empty for another name.
TriangleSoup NamedScene(const std::string& name);

// Rays along the axes (directions with +-0 components) from points on the
// integer and half-integer planes of VoxelGrid(10, ...), which are its
// leaves' box faces too.
std::vector<Ray> GridAxisRays(int count, uint32_t seed);

// The shadow ray from `hit` (on soup's triangle hit.tri) to `light`, as the
// renderer spawns it (spawn.h SpawnShadowRay from the hit point with its
// error bounds).
Ray ShadowRayFromHit(const TriangleSoup& soup, const Hit& hit, const Vec3& light);

// Whether two hits are the same bit for bit (triangle, t, u and v): how the
// packet tests compare a lane with the single-ray traversal.
bool BitwiseSameHit(const Hit& a, const Hit& b);

}  // namespace testing
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TEST_SCENES_H_
