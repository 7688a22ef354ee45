#include "cc/scenes/ply.h"

#include <string>

#include "cc/scenes/mesh.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

Mesh UnitCube() {
  Mesh m;
  AddBox(m, {0, 0, 0}, {1, 2, 3});
  return m;
}

TEST(Ply, HeaderAndSizeAreExact) {
  const std::string bytes = EncodePly(UnitCube());
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment kdtree_repro cc/scenes generator\n"
      "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.size(), header.size() + 8 * 12 + 12 * 13);
  // Little-endian float 1.0f = 00 00 80 3f: vertex 1 is (1, 0, 0).
  EXPECT_EQ(bytes.substr(header.size() + 12, 4), std::string("\x00\x00\x80\x3f", 4));
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
