// Smoke run of the traversal fuzz case (traversal_fuzz.h): seeded random
// inputs of every alphabet, plus a few hand-made ones. The long run is the
// libFuzzer target traversal_fuzzer.cc (cc/robust/fuzz.sh).
#include "cc/robust/traversal_fuzz.h"

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/traversal.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

TEST(TraversalFuzz, SeededInputsAgreeWithBruteForce) {
  std::mt19937 rng(1);
  size_t bad = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> data(rng() % 1200);
    for (uint8_t& b : data) b = static_cast<uint8_t>(rng());
    if (!data.empty()) data[0] = static_cast<uint8_t>((data[0] & ~3u) | (i % 3));
    bad += TraversalFuzzCase(data.data(), data.size());
  }
  EXPECT_EQ(bad, 0u);
}

// Found by the seeded run above (case 33): a reference box reaching far
// beyond a tiny node made the binned SAH's bin index (x - lo) * bins / extent
// exceed INT_MAX; the float-to-int conversion is undefined (INT_MIN on x86)
// and the bin counters were written out of bounds (a crash in SweepAxis).
// Minimal scene: a unit triangle through a cluster 1e-10 across.
TEST(TraversalFuzz, BigTriangleThroughTinyClusterBuilds) {
  TriangleSoup soup;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1e-10f);
  for (int i = 0; i < 400; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    soup.Add(a, a + Vec3(u(rng), 0, 0) * 0.01f, a + Vec3(0, u(rng), u(rng)) * 0.01f);
  }
  soup.Add({-1, -1, -1}, {1, 2e-11f, 3e-11f}, {4e-11f, 1, -1});
  const BruteForce bf(soup);
  for (const std::string& name : PresetNames()) {
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset(name));
    ASSERT_TRUE(tree.ok()) << name << ": " << tree.status();
    for (int i = 0; i < 200; ++i) {
      const Ray ray{Vec3(u(rng), u(rng), -1), Vec3(1e-11f, -2e-11f, 1)};
      const Hit want = bf.Intersect(ray), got = Intersect(*tree, ray);
      EXPECT_EQ(got.tri, want.tri) << name;
      EXPECT_EQ(got.t, want.t) << name;
    }
  }
}

// Found by a one-hour libFuzzer run (cc/robust/fuzz.sh, 2026-12-03): a few
// overlapping triangles that no plane separates, which the report's presets
// split to depth 24 (millions of nodes: 197 s under ASan). The builds now stop
// at their budget.
TEST(TraversalFuzz, AnUnseparablePileStopsAtTheBuildBudget) {
  const std::vector<uint8_t> pile = {
      0x2e, 0x0,  0x0,  0x0,  0xff, 0xcc, 0x0,  0x7e, 0xff, 0xff, 0x0,  0x0,  0x0,  0xff, 0xcc,
      0x0,  0x7e, 0xff, 0xff, 0xea, 0x5,  0x60, 0xff, 0xff, 0xff, 0x0,  0x0,  0x0,  0x0,  0x15,
      0x0,  0x0,  0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x0,  0x0,  0x0,  0x0,  0xea,
      0x5,  0x60, 0xff, 0xff, 0xff, 0x0,  0x0,  0x0,  0x0,  0x15, 0x0,  0x0,  0xff, 0xff, 0x0,
      0x0,  0x3,  0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x0,  0x0,  0x0,  0x0,  0x0,  0x0,  0x0,
      0x0,  0xff, 0x25, 0xff, 0xff, 0xff, 0x1,  0x0,  0x0,  0x5};
  EXPECT_EQ(TraversalFuzzCase(pile.data(), pile.size()), 0u);
}

TEST(TraversalFuzz, EmptyAndTinyInputs) {
  EXPECT_EQ(TraversalFuzzCase(nullptr, 0), 0u);
  const uint8_t one[] = {7};
  EXPECT_EQ(TraversalFuzzCase(one, 1), 0u);
  std::vector<uint8_t> nan_bytes(400, 0xff);  // NaN coordinates everywhere
  EXPECT_EQ(TraversalFuzzCase(nan_bytes.data(), nan_bytes.size()), 0u);
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
