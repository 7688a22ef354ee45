#include "cc/render/cost_image.h"

#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/test_scene.h"
#include "cc/render/traversal_counts.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string ReadGz(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  EXPECT_NE(f, nullptr);
  std::string out;
  char buf[65536];
  int n;
  while ((n = gzread(f, buf, sizeof(buf))) > 0) out.append(buf, n);
  gzclose(f);
  return out;
}

TEST(CostImage, PixelsSumToTheCountingPassTotals) {
  const TriangleSoup soup = testing::SphereOnGround();
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("clipping-pruning"));
  ASSERT_TRUE(tree.ok());
  const View view = testing::SphereView(48, 32);
  RenderOptions opt;
  opt.record_rays = true;
  const RenderResult r = Render(soup, KdTreeTracer(*tree), view, opt);
  CostImage image(view.width, view.height);
  const RayCounts counts = CountTraversal(*tree, r.rays, &image);
  const RayCounts plain = CountTraversal(*tree, r.rays);
  EXPECT_EQ(counts.all.inner_visits, plain.all.inner_visits);
  EXPECT_EQ(counts.all.triangle_tests, plain.all.triangle_tests);
  EXPECT_EQ(counts.result_mismatches, 0u);
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      EXPECT_EQ(image.at(x, y, RayKind::kPrimary, kCostRays), 1u) << "one primary ray per pixel";
    }
  }
  for (int kind = 0; kind < kNumRayKinds; ++kind) {
    uint64_t rays = 0, inner = 0, tests = 0;
    for (int y = 0; y < view.height; ++y) {
      for (int x = 0; x < view.width; ++x) {
        rays += image.at(x, y, static_cast<RayKind>(kind), kCostRays);
        inner += image.at(x, y, static_cast<RayKind>(kind), kCostInnerVisits);
        tests += image.at(x, y, static_cast<RayKind>(kind), kCostTriangleTests);
      }
    }
    EXPECT_EQ(rays, counts.by_kind[kind].rays) << "kind " << kind;
    EXPECT_EQ(inner, counts.by_kind[kind].inner_visits) << "kind " << kind;
    EXPECT_EQ(tests, counts.by_kind[kind].triangle_tests) << "kind " << kind;
  }
  EXPECT_GT(counts.by_kind[static_cast<int>(RayKind::kShadow)].triangle_tests, 0u);
}

TEST(CostImage, WritesWhatNumpyReads) {
  CostImage image(3, 2);
  image.Add(4, RayKind::kShadow, 7, 9);
  image.Add(4, RayKind::kShadow, 1, 1);
  image.Add(0, RayKind::kPrimary, uint64_t{1} << 40, 2);  // saturates
  const std::string path = ::testing::TempDir() + "/cost.npy.gz";
  ASSERT_TRUE(WriteCostImageNpyGz(path, image).ok());
  const std::string bytes = ReadGz(path);
  // What numpy.save writes for an array of this dtype and shape.
  std::string dict = "{'descr': '<u4', 'fortran_order': False, 'shape': (2, 3, 3, 3), }";
  dict.append(128 - 10 - dict.size() - 1, ' ');  // to 128 bytes in all
  dict += "\n";
  const std::string header = std::string("\x93NUMPY\x01\x00", 8) + char(dict.size()) + '\0' + dict;
  ASSERT_EQ(bytes.size(), header.size() + 6 * kCostChannels * 4);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  std::vector<uint32_t> data(6 * kCostChannels);
  std::memcpy(data.data(), bytes.data() + header.size(), data.size() * 4);
  EXPECT_EQ(data, image.counts);
  EXPECT_EQ(image.at(1, 1, RayKind::kShadow, kCostRays), 2u);
  EXPECT_EQ(image.at(1, 1, RayKind::kShadow, kCostInnerVisits), 8u);
  EXPECT_EQ(image.at(1, 1, RayKind::kShadow, kCostTriangleTests), 10u);
  EXPECT_EQ(image.at(0, 0, RayKind::kPrimary, kCostInnerVisits), 0xffffffffu);
  EXPECT_EQ(image.at(0, 0, RayKind::kPrimary, kCostTriangleTests), 2u);
}

TEST(CostImage, AnUnwritablePathIsAnError) {
  const absl::Status st = WriteCostImageNpyGz("/nonexistent-dir/x.npy.gz", CostImage(2, 2));
  EXPECT_FALSE(st.ok());
  EXPECT_NE(std::string(st.message()).find("/nonexistent-dir/x.npy.gz"), std::string::npos);
}

}  // namespace
}  // namespace kdtree
