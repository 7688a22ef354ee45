#include <cmath>
#include <string>
#include <vector>

#include "cc/scenes/assembly.h"
#include "cc/scenes/courtyard.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/plant.h"
#include "cc/scenes/ply.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

// A part made of `boxes` unit boxes stacked (12 triangles each), in
// arbitrary units and offset, to check normalisation.
Part BoxPart(const std::string& role, float height, int boxes) {
  Mesh m;
  for (int i = 0; i < boxes; ++i) AddBox(m, Vec3(10, 5 + 2 * i, 3), Vec3(12, 7 + 2 * i, 4));
  return Part{role, height, NormalisePart(m, height)};
}

TEST(Assembly, NormalisedPartStandsOnOriginAtItsHeight) {
  const Part p = BoxPart("tree", 6, 3);
  const AABB b = p.mesh.Bounds();
  EXPECT_FLOAT_EQ(b.lo.y, 0);
  EXPECT_FLOAT_EQ(b.hi.y, 6);
  EXPECT_FLOAT_EQ(b.lo.x + b.hi.x, 0);
  EXPECT_FLOAT_EQ(b.lo.z + b.hi.z, 0);
}

TEST(Assembly, TubeAndFanCounts) {
  Mesh m;
  AddTube(m, Vec3(0, 0, 0), Vec3(0, 3, 0), 0.5f, 8, 3);
  EXPECT_EQ(m.TriangleCount(), 2u * 8 * 3);
  for (int64_t n : {1, 2, 3, 17}) {
    Mesh f;
    AddFan(f, Vec3(1, 2, 3), 1.0f, n);
    EXPECT_EQ(static_cast<int64_t>(f.TriangleCount()), n);
    for (const Vec3& p : f.vertices) EXPECT_EQ(p.y, 2.0f);
  }
}

TEST(Assembly, ReadPartRejectsBadSpecs) {
  EXPECT_FALSE(ReadPart("tree:6").ok());
  EXPECT_FALSE(ReadPart("tree:-1:/nonexistent.ply").ok());
  EXPECT_FALSE(ReadPart("tree:6:/nonexistent.ply").ok());
}

TEST(Plant, ExactCountDeterministicAndNeedsMachine) {
  const std::vector<Part> parts = {BoxPart("machine", 3, 40), BoxPart("tank", 5, 2),
                                   BoxPart("tower", 30, 4)};
  PlantConfig c;
  c.target_triangles = 250001;
  absl::StatusOr<Mesh> a = GeneratePlant(c, parts), b = GeneratePlant(c, parts);
  ASSERT_TRUE(a.ok()) << a.status();
  EXPECT_EQ(a->TriangleCount(), 250001u);
  EXPECT_EQ(EncodePly(*a), EncodePly(*b));
  c.seed = 2;
  EXPECT_NE(EncodePly(*GeneratePlant(c, parts)), EncodePly(*a));
  EXPECT_FALSE(GeneratePlant(c, {BoxPart("tank", 5, 2)}).ok());
}

TEST(Courtyard, ExactCountDeterministicAndInsideTheArcade) {
  const std::vector<Part> parts = {BoxPart("tree", 8, 200), BoxPart("tree", 6, 150),
                                   BoxPart("plant", 1, 20),  BoxPart("table", 0.75f, 5),
                                   BoxPart("chair", 0.9f, 8), BoxPart("column", 3, 6),
                                   BoxPart("fountain", 1.5f, 30)};
  CourtyardConfig c;
  c.target_triangles = 300007;
  absl::StatusOr<Mesh> a = GenerateCourtyard(c, parts), b = GenerateCourtyard(c, parts);
  ASSERT_TRUE(a.ok()) << a.status();
  EXPECT_EQ(a->TriangleCount(), 300007u);
  EXPECT_EQ(EncodePly(*a), EncodePly(*b));
  const AABB box = a->Bounds();
  EXPECT_GE(box.lo.y, -1e-3f);
  EXPECT_LE(box.hi.y, 8 * 1.15f + 1e-3f);  // the tallest tree, at its largest scale
  EXPECT_FALSE(GenerateCourtyard(c, {BoxPart("plant", 1, 2)}).ok());
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
