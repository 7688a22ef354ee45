#include "cc/bench/twice_tracer.h"

#include <vector>

#include "cc/geometry/ray.h"
#include "cc/render/tracer.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace bench {
namespace {

// Counts its calls and answers by the ray's tmax: a hit at t = tmax on
// triangle 7 when tmax > 1, occluded when tmax > 1.
class CountingTracer : public Tracer {
 public:
  std::string name() const override { return "counting"; }
  Hit Intersect(const Ray& ray) const override {
    ++single;
    Hit h;
    if (ray.tmax > 1) {
      h.tri = 7;
      h.t = ray.tmax;
    }
    return h;
  }
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override {
    ++single;
    origins.push_back(origin_tri);
    return ray.tmax > 1;
  }
  void IntersectPacket(const Ray* rays, int n, Hit* hits) const override {
    ++packets;
    for (int i = 0; i < n; ++i) hits[i] = Intersect(rays[i]);
  }
  void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                      bool* occluded) const override {
    ++packets;
    for (int i = 0; i < n; ++i) occluded[i] = Occluded(rays[i], origin_tris ? origin_tris[i] : 0);
  }
  mutable int single = 0, packets = 0;
  mutable std::vector<uint32_t> origins;
};

Ray RayTo(float tmax) {
  Ray r;
  r.origin = Vec3(0, 0, 0);
  r.dir = Vec3(0, 0, 1);
  r.tmin = 0;
  r.tmax = tmax;
  return r;
}

TEST(TwiceTracerTest, EverySingleQueryTwiceWithTheInnerAnswer) {
  CountingTracer inner;
  const TwiceTracer twice(&inner);
  EXPECT_EQ(twice.name(), "counting");
  EXPECT_EQ(&twice.inner(), &inner);
  const Hit h = twice.Intersect(RayTo(2));
  EXPECT_EQ(h.tri, 7u);
  EXPECT_EQ(h.t, 2.0f);
  EXPECT_EQ(inner.single, 2);
  EXPECT_FALSE(twice.Intersect(RayTo(0.5f)).hit());
  EXPECT_EQ(inner.single, 4);
  EXPECT_TRUE(twice.Occluded(RayTo(2), 5));
  EXPECT_FALSE(twice.Occluded(RayTo(0.5f), 6));
  EXPECT_EQ(inner.single, 8);
  EXPECT_EQ(inner.origins, (std::vector<uint32_t>{5, 5, 6, 6}));
}

TEST(TwiceTracerTest, EveryPacketTwiceWithTheInnerAnswers) {
  CountingTracer inner;
  const TwiceTracer twice(&inner);
  const Ray rays[3] = {RayTo(2), RayTo(0.5f), RayTo(3)};
  Hit hits[3];
  twice.IntersectPacket(rays, 3, hits);
  EXPECT_EQ(inner.packets, 2);
  EXPECT_EQ(hits[0].t, 2.0f);
  EXPECT_FALSE(hits[1].hit());
  EXPECT_EQ(hits[2].t, 3.0f);
  const uint32_t origins[3] = {1, 2, 3};
  bool occluded[3] = {false, true, false};
  twice.OccludedPacket(rays, 3, origins, occluded);
  EXPECT_EQ(inner.packets, 4);
  EXPECT_TRUE(occluded[0]);
  EXPECT_FALSE(occluded[1]);
  EXPECT_TRUE(occluded[2]);
  EXPECT_EQ(inner.origins, (std::vector<uint32_t>{1, 2, 3, 1, 2, 3}));
}

}  // namespace
}  // namespace bench
}  // namespace kdtree
