#include "cc/render/png.h"

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TempPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

uint32_t BigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

TEST(Png, WritesReadableFile) {
  const int w = 37, h = 21;
  std::vector<uint8_t> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 7);
  const std::string path = TempPath("t.png");
  ASSERT_TRUE(WritePngRgb8(path, w, h, rgb).ok());
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 8u + 25u + 12u);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(sig, sig + 8, bytes.begin()));
  // IHDR: length 13, type, width, height, bit depth 8, colour type 2 (RGB).
  EXPECT_EQ(BigEndian32(&bytes[8]), 13u);
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  EXPECT_EQ(BigEndian32(&bytes[16]), static_cast<uint32_t>(w));
  EXPECT_EQ(BigEndian32(&bytes[20]), static_cast<uint32_t>(h));
  EXPECT_EQ(bytes[24], 8);
  EXPECT_EQ(bytes[25], 2);
  EXPECT_EQ(std::string(bytes.end() - 8, bytes.end() - 4), "IEND");
}

TEST(Png, ErrorsNameTheFile) {
  const std::vector<uint8_t> rgb(4 * 4 * 3);
  absl::Status st = WritePngRgb8("/nonexistent/dir/x.png", 4, 4, rgb);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("/nonexistent/dir/x.png"), std::string::npos);
  st = WritePngRgb8(TempPath("y.png"), 5, 4, rgb);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("y.png"), std::string::npos);
}

}  // namespace
}  // namespace kdtree
