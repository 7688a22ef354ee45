// Hard case 4: a flat scene (800 overlapping triangles in the plane z = 0, so
// the root box has zero thickness) and a voxel-world block scene (every face in an integer
// plane, which is also where the split planes go). Random rays, a 200x200
// camera, axis-parallel rays, and rays in or grazing the planes (direction
// component +0, -0, 1e-38, 1e-7 across the plane). Every preset against brute
// force, both modes.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

// Rays with origin in the plane `axis = value` (and just off it) whose
// direction crosses the plane at a grazing angle or not at all.
void AddPlaneRays(const AABB& box, int axis, float value, int count, std::mt19937* rng,
                  std::vector<Ray>* rays) {
  std::uniform_real_distribution<float> unit(0, 1), sym(-1, 1);
  const float across[] = {0.0f, -0.0f, 1e-38f, -1e-38f, 1e-7f, -1e-7f, 1e-3f};
  const float offsets[] = {0.0f, 1e-7f, -1e-7f};
  for (int i = 0; i < count; ++i) {
    Ray r;
    for (int k = 0; k < 3; ++k) {
      r.origin[k] = box.lo[k] - 0.2f * (box.hi[k] - box.lo[k] + 1) +
                    1.4f * (box.hi[k] - box.lo[k] + 1) * unit(*rng);
      r.dir[k] = sym(*rng);
    }
    r.origin[axis] = value + offsets[i % 3];
    r.dir[axis] = across[(i / 3) % 7];
    rays->push_back(r);
  }
}

std::vector<Ray> AxisRaysAtVertices(const TriangleSoup& soup) {
  AxisGrid grid;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    grid.points[a] = GridPoints(WithMidpoints(Sample(VertexCoordinates(soup, b), 150)),
                                WithMidpoints(Sample(VertexCoordinates(soup, c), 150)), 4000, 8);
  }
  return AxisParallelRays(soup.Bounds(), grid);
}

TEST(FlatScene, EveryPresetMatchesBruteForce) {
  const TriangleSoup soup = testing::FlatScene(800, 4);
  const AABB box = soup.Bounds();
  ASSERT_EQ(box.lo.z, box.hi.z) << "the root box should have zero thickness";
  std::mt19937 rng(41);
  std::vector<Ray> rays = testing::RandomRays(soup, 20000, 42);
  const std::vector<Ray> cam = testing::CameraRays(soup, 200, 200);
  rays.insert(rays.end(), cam.begin(), cam.end());
  const std::vector<Ray> axis = AxisRaysAtVertices(soup);
  rays.insert(rays.end(), axis.begin(), axis.end());
  AddPlaneRays(box, 2, 0.0f, 20000, &rng, &rays);
  // Straight down and up through the plane at vertex coordinates.
  for (size_t i = 0; i < soup.v.size(); i += 7) {
    const Vec3& p = soup.v[i];
    rays.push_back(Ray{{p.x, p.y, 1}, {0, 0, -1}});
    rays.push_back(Ray{{p.x, p.y, -1}, {-0.0f, 0.0f, 1}});
  }
  std::printf("flat: %zu triangles, %zu rays\n", soup.size(), rays.size());
  std::fflush(stdout);
  ExpectNoMismatches("flat", CheckAllPresets("flat", soup, rays, BothModes()));
}

TEST(BlockWorld, EveryPresetMatchesBruteForce) {
  const TriangleSoup soup = testing::VoxelGrid(16, 10, 16, 5);
  const AABB box = soup.Bounds();
  std::mt19937 rng(43);
  std::vector<Ray> rays = testing::RandomRays(soup, 20000, 44);
  const std::vector<Ray> cam = testing::CameraRays(soup, 200, 200);
  rays.insert(rays.end(), cam.begin(), cam.end());
  const std::vector<Ray> axis = AxisRaysAtVertices(soup);
  rays.insert(rays.end(), axis.begin(), axis.end());
  for (int axis_k = 0; axis_k < 3; ++axis_k) {
    for (int plane = 0; plane <= 16; plane += 3) AddPlaneRays(box, axis_k, plane, 700, &rng, &rays);
  }
  std::printf("blocks: %zu triangles, %zu rays\n", soup.size(), rays.size());
  std::fflush(stdout);
  CheckOptions options;
  options.include_seed = true;
  ExpectNoMismatches("blocks", CheckAllPresets("blocks", soup, rays, BothModes(), options));
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
