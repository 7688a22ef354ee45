// The suite's ray sample (KDTREE_ROBUST_RAY_STRIDE): every k-th packet of 4
// rays is checked, on every preset, and the records count what was checked.
#include "cc/robust/preset_check.h"

#include <cstdlib>
#include <vector>

#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

TEST(RaySample, EveryThirdPacketOfFourIsChecked) {
  // Read once per process: set before the first call.
  ASSERT_EQ(setenv("KDTREE_ROBUST_RAY_STRIDE", "3", 1), 0);
  EXPECT_EQ(RayStride(), 3u);
  std::vector<int> v(26);
  for (int i = 0; i < 26; ++i) v[i] = i;
  EXPECT_EQ(Sample(v), (std::vector<int>{0, 1, 2, 3, 12, 13, 14, 15, 24, 25}));

  const TriangleSoup soup = SmallScene("tiny");
  std::vector<Ray> rays;
  for (int i = 0; i < 40; ++i) {
    rays.push_back(Ray{Vec3(0.1f * i - 2, 0.3f, -5), Vec3(0, 0, 1)});
  }
  CheckOptions options;
  options.presets = {"default", "sah-packet"};
  const std::vector<CheckResult> results =
      CheckAllPresets("sample", soup, rays, BothModes(), options);
  ASSERT_EQ(results.size(), 4u);
  for (const CheckResult& r : results) {
    EXPECT_EQ(r.rays, 16u);  // packets 0, 3, 6 and 9 of 10
    EXPECT_EQ(r.mismatches, 0u);
  }
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
