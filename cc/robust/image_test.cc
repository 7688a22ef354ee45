// Hard case 9: the image check. For each small scene, every preset's 200x200
// primary-ray hit buffer (triangle, t, u, v per pixel) equals the brute-force
// one pixel for pixel, in both modes. Two cameras per scene: the pinhole of
// test_scenes.h (CameraRays) and one looking straight down -y from above the
// box centre, so that the centre row and column of rays lie exactly in axis
// planes (direction components +0 and -0).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cc/kdtree/test_scenes.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

constexpr int kSize = 200;

// A pinhole above the box looking down -y; pixel (x, y) has direction
// (sx, -1, sy) with sx, sy symmetric around 0 and exactly 0 (sign kept) in the
// middle, which an even size hits between pixels, so the grid is 201 wide.
std::vector<Ray> TopDownRays(const TriangleSoup& soup) {
  const AABB box = soup.Bounds();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  const Vec3 ext = box.Extent();
  const float size = std::fmax(std::fmax(ext.x, ext.z), 1e-3f);
  const Vec3 eye(centre.x, box.hi.y + size, centre.z);
  std::vector<Ray> rays;
  const int n = kSize + 1;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float sx = 0.6f * (x - kSize / 2) / (kSize / 2);
      const float sy = 0.6f * (y - kSize / 2) / (kSize / 2);
      rays.push_back(Ray{eye, Vec3(x < kSize / 2 ? -std::fabs(sx) : sx, -1,
                                   y < kSize / 2 ? -std::fabs(sy) : sy)});
      if (x == kSize / 2) rays.back().dir.x = (y % 2) ? -0.0f : 0.0f;
      if (y == kSize / 2) rays.back().dir.z = (x % 2) ? -0.0f : 0.0f;
    }
  }
  return rays;
}

class Image : public ::testing::TestWithParam<std::string> {};

TEST_P(Image, EveryPresetEqualsBruteForcePixelForPixel) {
  const std::string scene = GetParam();
  const TriangleSoup soup = SmallScene(scene);
  ASSERT_FALSE(soup.empty());
  std::vector<Ray> rays = testing::CameraRays(soup, kSize, kSize);
  const std::vector<Ray> top = TopDownRays(soup);
  rays.insert(rays.end(), top.begin(), top.end());
  CheckOptions options;
  options.include_seed = true;
  ExpectNoMismatches("image/" + scene,
                     CheckAllPresets("image/" + scene, soup, rays, BothModes(), options));
}

INSTANTIATE_TEST_SUITE_P(Scenes, Image, ::testing::ValuesIn(SmallSceneNames()),
                         SceneParamName());

}  // namespace
}  // namespace robust
}  // namespace kdtree
