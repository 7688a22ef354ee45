// Hard case 2: rays whose origin lies exactly on a split plane (every split of
// every preset's tree), with the direction component on that axis positive,
// negative, +0 and -0; also origins on the line where two split planes of
// different axes meet. Every preset against brute force, both modes.
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

class SplitOrigins : public ::testing::TestWithParam<std::string> {};

TEST_P(SplitOrigins, EveryPresetMatchesBruteForce) {
  const std::string scene = GetParam();
  const TriangleSoup soup = SmallScene(scene);
  ASSERT_FALSE(soup.empty());
  std::set<std::pair<int, float>> planes;
  std::vector<std::string> presets = CheckedPresets();
  presets.push_back("pruning-seed");
  for (const std::string& name : presets) {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, *ConfigFor(name));
    ASSERT_TRUE(tree.ok()) << tree.status();
    const std::vector<std::vector<float>> splits = SplitValues(*tree);
    for (int a = 0; a < 3; ++a) {
      for (float s : splits[a]) planes.insert({a, s});
    }
  }
  const std::vector<std::pair<int, float>> plane_list(planes.begin(), planes.end());
  const AABB box = soup.Bounds();
  const Vec3 ext = box.Extent();
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> unit(0, 1), sym(-1, 1);
  auto in_box = [&](int k) { return box.lo[k] - 0.1f * ext[k] + 1.2f * ext[k] * unit(rng); };
  std::vector<Ray> rays;
  auto add_fan = [&](const Vec3& origin, int axis) {
    // Direction component on `axis`: +, -, +0, -0; the others random.
    for (float along : {0.2f + unit(rng), -0.2f - unit(rng), 0.0f, -0.0f}) {
      Ray r;
      r.origin = origin;
      for (int k = 0; k < 3; ++k) r.dir[k] = sym(rng);
      r.dir[axis] = along;
      if (r.dir[(axis + 1) % 3] == 0 && r.dir[(axis + 2) % 3] == 0) r.dir[(axis + 1) % 3] = 1;
      rays.push_back(r);
    }
  };
  for (const auto& [axis, split] : plane_list) {
    for (int k = 0; k < 3; ++k) {  // random points of the plane
      Vec3 o(in_box(0), in_box(1), in_box(2));
      o[axis] = split;
      add_fan(o, axis);
    }
    // A point of the plane at a vertex's other coordinates (on edges in-plane).
    Vec3 o = soup.v[rng() % soup.v.size()];
    o[axis] = split;
    add_fan(o, axis);
  }
  // Lines where two planes of different axes meet.
  for (size_t i = 0; i < plane_list.size(); ++i) {
    const auto& [a1, s1] = plane_list[i];
    const auto& [a2, s2] = plane_list[rng() % plane_list.size()];
    if (a1 == a2) continue;
    Vec3 o(in_box(0), in_box(1), in_box(2));
    o[a1] = s1;
    o[a2] = s2;
    add_fan(o, a1);
    add_fan(o, a2);
  }
  std::printf("%s: %zu triangles, %zu distinct split planes over the presets, %zu rays\n",
              scene.c_str(), soup.size(), plane_list.size(), rays.size());
  CheckOptions options;
  options.include_seed = true;
  ExpectNoMismatches("split_origins/" + scene,
                     CheckAllPresets("split_origins/" + scene, soup, rays, BothModes(), options));
}

INSTANTIATE_TEST_SUITE_P(Scenes, SplitOrigins, ::testing::ValuesIn(SmallSceneNames()),
                         SceneParamName());

}  // namespace
}  // namespace robust
}  // namespace kdtree
