#include "cc/bench/ray_classes.h"

#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/traversal.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/test_scene.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace bench {
namespace {

class RayClassesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    absl::StatusOr<Config> config = Preset("sah-packet");
    ASSERT_TRUE(config.ok());
    absl::StatusOr<KdTree> t = BuildKdTree(soup_, *config);
    ASSERT_TRUE(t.ok());
    tree_ = *std::move(t);
    RenderOptions o;
    o.record_rays = true;
    KdTreeTracer kd(tree_);
    rec_ = Render(soup_, kd, testing::SphereView(48, 32), o);
  }
  TriangleSoup soup_ = testing::SphereOnGround();
  KdTree tree_;
  RenderResult rec_;
};

TEST_F(RayClassesTest, EveryRayInTheClassOfWhatItDoes) {
  const std::vector<RayClass> classes = ClassifyRays(rec_.rays, tree_);
  std::vector<std::string> names;
  size_t total = 0;
  for (const RayClass& c : classes) {
    names.push_back(c.name);
    total += c.rays.size();
    for (size_t i = 0; i < c.rays.size(); ++i) {
      TraversalCounters counters;
      const Hit h = Intersect(tree_, c.rays[i], TraversalOptions(), &counters);
      const bool reached = counters.inner_visits + counters.leaf_visits > 0;
      if (c.name == "camera_no_node") {
        EXPECT_FALSE(reached);
      } else if (c.name == "camera_miss") {
        EXPECT_TRUE(reached && !h.hit());
      } else if (c.name == "camera_hit") {
        EXPECT_TRUE(h.hit());
      }
    }
    EXPECT_EQ(c.any_hit, c.name == "shadow");
    EXPECT_EQ(c.origin_tris.size(), c.any_hit ? c.rays.size() : 0u);
  }
  // The view sees sky beside the scene's box, the box's empty corners, the
  // sphere and the ground; one light, no AO.
  EXPECT_EQ(names, (std::vector<std::string>{"camera_no_node", "camera_miss", "camera_hit",
                                             "shadow"}));
  EXPECT_EQ(total, rec_.rays.size());
  // A shadow ray's origin triangle is its pixel's primary hit.
  for (uint32_t t : classes.back().origin_tris) EXPECT_LT(t, soup_.size());
}

TEST_F(RayClassesTest, TimesEveryClassForEveryTracerPairedWithTheReference) {
  const std::vector<RayClass> classes = ClassifyRays(rec_.rays, tree_);
  KdTreeTracer kd(tree_);
  const BruteForce bf(soup_);
  BruteForceTracer brute(bf);
  std::vector<RenderVariant> tracers;
  tracers.push_back(RenderVariant{"kd_origin", &kd, false, true, ""});
  tracers.push_back(RenderVariant{"brute", &brute, false, false, ""});
  const Json j = TimeRayClasses(classes, tracers, "brute", 1, 3);
  EXPECT_EQ(j["rounds"], 3);
  ASSERT_EQ(j["classes"].size(), classes.size());
  for (const RayClass& c : classes) {
    const Json& e = j["classes"][c.name];
    EXPECT_EQ(e["rays"], c.rays.size());
    EXPECT_GT(e["ns_per_ray"]["kd_origin"].get<double>(), 0.0);
    EXPECT_GT(e["ns_per_ray"]["brute"].get<double>(), 0.0);
    EXPECT_EQ(e["ns_runs"]["kd_origin"].size(), 3u);
    const Json& over = e["brute_over"]["kd_origin"];
    EXPECT_LE(over["min"].get<double>(), over["median"].get<double>());
    EXPECT_LE(over["median"].get<double>(), over["max"].get<double>());
    EXPECT_FALSE(e["brute_over"].contains("brute"));
  }
  // Without the reference among the tracers: times only.
  const Json alone = TimeRayClasses(classes, tracers, "embree", 0, 1);
  EXPECT_FALSE(alone["classes"]["shadow"].contains("embree_over"));
}

}  // namespace
}  // namespace bench
}  // namespace kdtree
