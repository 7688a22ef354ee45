#include "cc/render/compare.h"

#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/render/exact_check.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/ray_record.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

// Every triangle checked in exact arithmetic (exact_check.h): the right
// answer, slowly. Closest hit by the (rounded) exact t.
class ExactTracer : public Tracer {
 public:
  explicit ExactTracer(const TriangleSoup& soup) : soup_(soup) {}
  std::string name() const override { return "exact"; }
  Hit Intersect(const Ray& ray) const override {
    Hit best;
    for (uint32_t i = 0; i < soup_.size(); ++i) {
      const ExactTriangleHit e = ExactIntersect(ray, soup_.a(i), soup_.b(i), soup_.c(i));
      if (e.hit && Closer(static_cast<float>(e.t), i, best)) {
        best.tri = i;
        best.t = static_cast<float>(e.t);
      }
    }
    return best;
  }
  bool Occluded(const Ray& ray, uint32_t) const override { return Intersect(ray).hit(); }

 private:
  const TriangleSoup& soup_;
};

// Brute force that never sees triangle 0: a wrong tracer.
class MissesTriangleZero : public Tracer {
 public:
  explicit MissesTriangleZero(const TriangleSoup& soup) : soup_(soup) {}
  std::string name() const override { return "broken"; }
  Hit Intersect(const Ray& ray) const override {
    std::vector<uint32_t> others;
    for (uint32_t i = 1; i < soup_.size(); ++i) others.push_back(i);
    return BruteForce(soup_).Intersect(ray, others);
  }
  bool Occluded(const Ray& ray, uint32_t) const override { return Intersect(ray).hit(); }

 private:
  const TriangleSoup& soup_;
};

// Claims a hit on triangle 0 at t for every ray (by default a tiny t, as
// Embree does on the shadow ray of a test below: its own rounding of t).
class ClaimsTriangleZero : public Tracer {
 public:
  explicit ClaimsTriangleZero(float t = 2.44193465e-08f) : t_(t) {}
  std::string name() const override { return "claims"; }
  Hit Intersect(const Ray&) const override {
    Hit h;
    h.tri = 0;
    h.t = t_;
    return h;
  }
  bool Occluded(const Ray&, uint32_t) const override { return true; }

 private:
  float t_;
};

RayRecord Record(const Ray& ray, RayKind kind, const Tracer& tracer) {
  return kind == RayKind::kPrimary ? PrimaryRecord(ray, tracer.Intersect(ray))
                                   : SecondaryRecord(ray, kind, tracer.Occluded(ray));
}

// A real shadow ray of the engine scene (pruning preset, manifest view): it
// leaves a surface 1e-3 behind a large, nearly parallel triangle and crosses it
// at t = 2.36e-6 (1.8e-3 world units). The watertight test's t bound used to
// reject that hit (a t_guard disagreement); t within the bound is now decided
// exactly (cc/geometry/exact_t.h), so the tracers agree: occluded.
TEST(Compare, ExactHitCloseToTheOriginIsFound) {
  TriangleSoup soup;
  soup.Add(Vec3(-224.000031f, 53.5317688f, 77.0521545f), Vec3(-224.000046f, 80.7639618f, 53.4683723f),
           Vec3(-224.000031f, 61.7991104f, 73.1961823f));
  Ray ray;
  ray.origin = Vec3(-224.001053f, 59.2209358f, 74.3958282f);
  ray.dir = Vec3(433.014038f, 523.352051f, 337.62915f);
  ray.tmin = 0.0f;
  ray.tmax = 1.0f;
  const BruteForce bf(soup);
  const BruteForceTracer watertight(bf);
  const ExactTracer exact(soup);
  const ExactTriangleHit e = ExactIntersect(ray, soup.a(0), soup.b(0), soup.c(0));
  ASSERT_TRUE(e.hit);
  EXPECT_NEAR(e.t, 2.36e-6, 0.01e-6);
  EXPECT_TRUE(watertight.Occluded(ray));
  EXPECT_EQ(watertight.Intersect(ray).tri, 0u);
  const Disagreements d =
      CompareTracers({Record(ray, RayKind::kShadow, watertight)}, soup, watertight, exact);
  EXPECT_EQ(d.all.total(), 0u) << d.ToJson();
}

// A real primary ray of the teapots scene that passes, exactly, 0.1 ulp
// outside an edge of triangle 0; the next surface is triangle 1. The watertight
// test without its exact fallback reported triangle 0; with it, triangle 1,
// as exact arithmetic does. A tracer that claims triangle 0 (at its plane's
// t) disagrees: grazing, and the reference is the one that is wrong.
TEST(Compare, HitJustOutsideAnEdgeIsGrazing) {
  TriangleSoup soup;
  soup.Add(Vec3(5.03153086f, 0.283207953f, 2.02320671f), Vec3(5.0413394f, 0.287568688f, 2.00816941f),
           Vec3(5.01601362f, 0.293907821f, 1.99966097f));
  soup.Add(Vec3(5.02814484f, 0.118860729f, 1.76349771f), Vec3(5.10360765f, 0.129305601f, 1.77940595f),
           Vec3(5.10112095f, 0.103911825f, 1.79138923f));
  Ray ray;
  ray.origin = Vec3(0, 21.9505997f, 30.8195f);
  ray.dir = Vec3(0.137871146f, -0.595067263f, -0.791761696f);
  const BruteForce bf(soup);
  const BruteForceTracer watertight(bf);
  const ExactTracer exact(soup);
  ASSERT_EQ(exact.Intersect(ray).tri, 1u);
  EXPECT_EQ(watertight.Intersect(ray).tri, 1u);
  const ClaimsTriangleZero claims(
      static_cast<float>(ExactIntersect(ray, soup.a(0), soup.b(0), soup.c(0)).t));
  const Disagreements d =
      CompareTracers({Record(ray, RayKind::kPrimary, claims)}, soup, claims, exact);
  EXPECT_EQ(d.all.t_differs, 1u) << d.ToJson();
  EXPECT_EQ(d.all.grazing, 1u) << d.ToJson();
  EXPECT_EQ(d.all.other(), 0u);
  EXPECT_EQ(d.all.reference_wrong, 1u);
}

// A real shadow ray of stk-ravenbridge-mansion (pruning preset): it was spawned
// from a surface and meets the plane of a long sliver triangle of the same
// wall exactly at t = -2.16e-7, behind its origin, within a few ulps of it.
// Embree reported a hit at t = 2.44e-8; the watertight test and exact
// arithmetic say: not occluded. That is "at_origin", and the other tracer is
// the wrong one.
TEST(Compare, CrossingWithinRoundingOfTheOriginIsAtOrigin) {
  TriangleSoup soup;
  soup.Add(Vec3(-173.437683f, 582.959717f, 302.369965f), Vec3(58.429287f, 68.1206436f, 354.512726f),
           Vec3(57.8742981f, 67.8721542f, 354.540558f));
  Ray ray;
  ray.origin = Vec3(-106.17572f, 433.502747f, 317.507294f);
  ray.dir = Vec3(737.5047f, 1137.07715f, 681.758667f);
  ray.tmin = 0.0f;
  ray.tmax = 1.0f;
  const ExactTriangleHit e = ExactIntersect(ray, soup.a(0), soup.b(0), soup.c(0));
  EXPECT_FALSE(e.hit);
  EXPECT_LT(e.t, 0.0);
  EXPECT_LE(e.plane_distance, kAtOriginUlps * FloatUlp(e.magnitude));
  EXPECT_GT(e.edge_distance, 100 * FloatUlp(e.magnitude));  // not grazing
  const BruteForce bf(soup);
  const BruteForceTracer watertight(bf);
  EXPECT_FALSE(watertight.Occluded(ray));
  const Disagreements d = CompareTracers({Record(ray, RayKind::kShadow, watertight)}, soup,
                                         watertight, ClaimsTriangleZero());
  EXPECT_EQ(d.all.total(), 1u) << d.ToJson();
  EXPECT_EQ(d.all.at_origin, 1u) << d.ToJson();
  EXPECT_EQ(d.all.other(), 0u);
  EXPECT_EQ(d.all.other_wrong, 1u);
}

// A tracer that loses a triangle disagrees far from any edge: "other", and
// the exact verdict names it.
TEST(Compare, MissedTriangleIsOther) {
  TriangleSoup soup;
  soup.Add(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  soup.Add(Vec3(0, 0, -1), Vec3(1, 0, -1), Vec3(0, 1, -1));
  const BruteForce bf(soup);
  const BruteForceTracer good(bf);
  const MissesTriangleZero broken(soup);
  std::vector<RayRecord> records;
  Ray primary;
  primary.origin = Vec3(0.25f, 0.25f, 1);
  primary.dir = Vec3(0, 0, -1);
  records.push_back(Record(primary, RayKind::kPrimary, good));  // t 1 vs t 2
  Ray shadow = primary;
  shadow.tmax = 1.5f;  // reaches triangle 0 only
  records.push_back(Record(shadow, RayKind::kShadow, good));
  Ray away = primary;
  away.origin = Vec3(5, 5, 1);  // misses both: agreement
  records.push_back(Record(away, RayKind::kPrimary, good));
  const Disagreements d = CompareTracers(records, soup, good, broken);
  EXPECT_EQ(d.all.rays, 3u);
  EXPECT_EQ(d.by_kind[0].t_differs, 1u) << d.ToJson();
  EXPECT_EQ(d.by_kind[1].hit_miss, 1u) << d.ToJson();
  EXPECT_EQ(d.all.other(), 2u);
  EXPECT_EQ(d.all.other_wrong, 2u);
  EXPECT_EQ(d.all.reference_wrong, 0u);
  ASSERT_EQ(d.examples.size(), 2u);
  EXPECT_NE(d.examples[0].find("wrong: broken"), std::string::npos) << d.examples[0];
}

// ToJson: the totals, then one object per ray kind, keys in a fixed order.
TEST(Compare, ToJsonFieldsInOrder) {
  Disagreements d;
  d.by_kind[0].rays = 5;
  d.by_kind[0].hit_miss = 2;
  d.by_kind[0].grazing = 1;
  d.by_kind[2].t_differs = 1;
  d.all.rays = 7;
  d.all.hit_miss = 2;
  d.all.t_differs = 1;
  d.all.grazing = 1;
  const nlohmann::ordered_json j = d.ToJson();
  const std::vector<std::string> counts = {"rays", "total", "grazing", "at_origin",
                                           "t_guard", "other", "hit_miss", "t_differs",
                                           "reference_wrong", "other_wrong"};
  std::vector<std::string> want = counts;
  for (const char* kind : {"primary", "shadow", "ao"}) want.push_back(kind);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  EXPECT_EQ(keys, want);
  EXPECT_EQ(j["total"].get<uint64_t>(), 3u);
  EXPECT_EQ(j["other"].get<uint64_t>(), 2u);
  EXPECT_EQ(j["primary"]["rays"].get<uint64_t>(), 5u);
  EXPECT_EQ(j["primary"]["other"].get<uint64_t>(), 1u);
  EXPECT_EQ(j["ao"]["t_differs"].get<uint64_t>(), 1u);
  std::vector<std::string> kind_keys;
  for (const auto& [key, value] : j["shadow"].items()) kind_keys.push_back(key);
  EXPECT_EQ(kind_keys, counts);
  EXPECT_EQ(j.dump().rfind("{\"rays\":7,\"total\":3,", 0), 0u) << j.dump();
}

}  // namespace
}  // namespace kdtree
