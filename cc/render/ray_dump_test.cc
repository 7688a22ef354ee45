#include "cc/render/ray_dump.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TempPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

RayDump Sample() {
  RayDump d;
  d.width = 3;
  d.height = 2;
  for (uint32_t i = 0; i < 10; ++i) {
    RayRecord r;
    r.origin = Vec3(0.1f * i, -1.0f, 2.5f);
    r.dir = Normalize(Vec3(1, static_cast<float>(i), 3));
    r.tmin = 0;
    r.tmax = i % 2 ? 4.5f : INFINITY;
    r.kind = static_cast<RayKind>(i % 3);
    r.hit = i % 2;
    r.light = static_cast<uint16_t>(i);
    r.pixel = i / 2;
    if (r.kind == RayKind::kPrimary && r.hit) {
      r.tri = 100 + i;
      r.t = 1.25f * i;
      r.u = 0.25f;
      r.v = 0.5f;
    }
    d.records.push_back(r);
  }
  return d;
}

TEST(RayDump, RoundTrip) {
  const RayDump d = Sample();
  const std::string path = TempPath("rays.bin");
  ASSERT_TRUE(WriteRayDump(path, d).ok());
  absl::StatusOr<RayDump> back = ReadRayDump(path);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->width, 3);
  EXPECT_EQ(back->height, 2);
  ASSERT_EQ(back->records.size(), d.records.size());
  for (size_t i = 0; i < d.records.size(); ++i) EXPECT_TRUE(back->records[i] == d.records[i]) << i;
  // Size: 32-byte header, 56 bytes per record, 8-byte checksum.
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  EXPECT_EQ(static_cast<size_t>(in.tellg()), 32u + 56u * d.records.size() + 8u);
}

TEST(RayDump, EmptyRoundTrip) {
  const std::string path = TempPath("empty.bin");
  ASSERT_TRUE(WriteRayDump(path, RayDump()).ok());
  absl::StatusOr<RayDump> back = ReadRayDump(path);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_TRUE(back->records.empty());
}

TEST(RayDump, DetectsCorruptionAndTruncation) {
  const std::string path = TempPath("bad.bin");
  ASSERT_TRUE(WriteRayDump(path, Sample()).ok());
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto write = [&](const std::string& b) { std::ofstream(path, std::ios::binary) << b; };
  std::string flipped = bytes;
  flipped[32 + 56 * 3 + 45] ^= 1;  // a bit of record 3's t
  write(flipped);
  absl::StatusOr<RayDump> r = ReadRayDump(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("checksum"), std::string::npos);
  write(bytes.substr(0, bytes.size() - 3));
  r = ReadRayDump(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("bad.bin"), std::string::npos);
  write("NOTRAYS!" + bytes.substr(8));
  EXPECT_FALSE(ReadRayDump(path).ok());
  EXPECT_FALSE(ReadRayDump(TempPath("absent.bin")).ok());
}

}  // namespace
}  // namespace kdtree
