// Hard case 1: axis-parallel rays (6 directions, each with the four +0/-0
// sign combinations of its zero components) on grids that include every vertex
// coordinate and every split value of every preset's tree, plus the midpoints
// between them. Every preset against brute force, both intersection modes.
#include <cstdio>
#include <string>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

class AxisRays : public ::testing::TestWithParam<std::string> {};

TEST_P(AxisRays, EveryPresetMatchesBruteForce) {
  const std::string scene = GetParam();
  const TriangleSoup soup = SmallScene(scene);
  ASSERT_FALSE(soup.empty());
  std::vector<std::vector<float>> values(3);
  for (int a = 0; a < 3; ++a) values[a] = VertexCoordinates(soup, a);
  std::vector<std::string> presets = CheckedPresets();
  presets.push_back("pruning-seed");
  size_t split_count = 0;
  for (const std::string& name : presets) {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, *ConfigFor(name));
    ASSERT_TRUE(tree.ok()) << tree.status();
    const std::vector<std::vector<float>> splits = SplitValues(*tree);
    for (int a = 0; a < 3; ++a) {
      values[a] = SortedUnion({values[a], splits[a]});
      split_count += splits[a].size();
    }
  }
  AxisGrid grid;
  size_t points = 0;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    grid.points[a] = GridPoints(WithMidpoints(values[b]), WithMidpoints(values[c]), 20000, 8);
    points += grid.points[a].size();
  }
  const std::vector<Ray> rays = AxisParallelRays(soup.Bounds(), grid);
  std::printf("%s: %zu triangles, %zu split values over the presets, values per axis %zu/%zu/%zu, "
              "%zu grid points, %zu rays\n",
              scene.c_str(), soup.size(), split_count, values[0].size(), values[1].size(),
              values[2].size(), points, rays.size());
  CheckOptions options;
  options.include_seed = true;
  ExpectNoMismatches("axis_rays/" + scene,
                     CheckAllPresets("axis_rays/" + scene, soup, rays, BothModes(), options));
}

INSTANTIATE_TEST_SUITE_P(Scenes, AxisRays,
                         ::testing::Values("tiny", "stairs", "voxels", "sphere", "thin", "flat"),
                         SceneParamName());

}  // namespace
}  // namespace robust
}  // namespace kdtree
