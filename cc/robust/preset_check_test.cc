// The suite's ray sample (KDTREE_ROBUST_RAY_STRIDE): every k-th packet of 16
// rays is checked, on every preset, and the records count what was checked.
#include "cc/robust/preset_check.h"

#include <cstdlib>
#include <vector>

#include "cc/kdtree/ray_packet.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

TEST(RaySample, EveryThirdPacketIsChecked) {
  static_assert(kRayPacketSize == 16, "the sample below is in packets of 16");
  // Read once per process: set before the first call.
  ASSERT_EQ(setenv("KDTREE_ROBUST_RAY_STRIDE", "3", 1), 0);
  EXPECT_EQ(RayStride(), 3u);
  std::vector<int> v(100), want;
  for (int i = 0; i < 100; ++i) {
    v[i] = i;
    // Packets 0, 3 and 6 of 7: rays 0-15, 48-63 and 96-99.
    if (i < 16 || (i >= 48 && i < 64) || i >= 96) want.push_back(i);
  }
  EXPECT_EQ(Sample(v), want);

  const TriangleSoup soup = SmallScene("tiny");
  std::vector<Ray> rays;
  for (int i = 0; i < 100; ++i) {
    rays.push_back(Ray{Vec3(0.04f * i - 2, 0.3f, -5), Vec3(0, 0, 1)});
  }
  CheckOptions options;
  options.presets = {"default", "sah-packet"};
  const std::vector<CheckResult> results =
      CheckAllPresets("sample", soup, rays, BothModes(), options);
  // Two presets in two modes, then the baseline in the watertight one.
  ASSERT_EQ(results.size(), 5u);
  EXPECT_EQ(results.back().preset, kTriangleBvhRow);
  EXPECT_EQ(results.back().mode, IntersectionMode::kWatertight);
  for (const CheckResult& r : results) {
    EXPECT_EQ(r.rays, 36u);  // packets 0, 3 and 6 of 7
    EXPECT_EQ(r.mismatches, 0u);
  }
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
