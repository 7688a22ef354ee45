#include "cc/render/replay_tracer.h"

#include "cc/kdtree/builder.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/test_scene.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

class Replay : public ::testing::TestWithParam<bool> {};  // packets or single rays

TEST_P(Replay, RendersTheRecordedImageAgain) {
  const TriangleSoup soup = testing::SphereOnGround();
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const KdTreeTracer kd(*tree);
  const View view = testing::SphereView(64, 48);
  RenderOptions opt;
  opt.packets = GetParam();
  opt.skip_origin = true;
  const RenderResult want = Render(soup, kd, view, opt);
  ASSERT_GT(want.s_hit, 0u) << "the sphere casts a shadow";

  ReplayTracer replay(kd);
  replay.Record();
  EXPECT_EQ(Render(soup, replay, view, opt).rgb, want.rgb);
  EXPECT_EQ(replay.recorded_hits(), want.primary.rays);
  EXPECT_EQ(replay.recorded_occlusions(), want.shadow.rays);
  for (int round = 0; round < 2; ++round) {
    replay.Rewind();
    const RenderResult got = Render(soup, replay, view, opt);
    EXPECT_FALSE(replay.overran());
    EXPECT_EQ(got.rgb, want.rgb);
    EXPECT_EQ(got.p_hit, want.p_hit);
    EXPECT_EQ(got.s_hit, want.s_hit);
  }
  // Without a rewind the answers have run out.
  Render(soup, replay, view, opt);
  EXPECT_TRUE(replay.overran());
}

INSTANTIATE_TEST_SUITE_P(Modes, Replay, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "packets" : "single";
                         });

}  // namespace
}  // namespace kdtree
