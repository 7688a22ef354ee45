#include "cc/io/soup_cache.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "absl/strings/string_view.h"
#include "cc/geometry/triangle.h"
#include "cc/io/mesh_loader.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TmpPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/" + name;
}

void WriteText(const std::string& path, absl::string_view text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr) << path;
  ASSERT_EQ(std::fwrite(text.data(), 1, text.size(), f), text.size());
  std::fclose(f);
}

// Overwrites one byte of the file at `offset` with its complement.
void FlipByte(const std::string& path, long offset) {
  std::FILE* f = std::fopen(path.c_str(), "r+b");
  ASSERT_NE(f, nullptr) << path;
  ASSERT_EQ(std::fseek(f, offset, SEEK_SET), 0);
  const int c = std::fgetc(f);
  ASSERT_NE(c, EOF);
  ASSERT_EQ(std::fseek(f, offset, SEEK_SET), 0);
  std::fputc(~c & 0xff, f);
  std::fclose(f);
}

TriangleSoup ThreeTriangles() {  // odd count: the checksum's last word is padded
  TriangleSoup s;
  s.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  s.Add({-1.5f, 2.25f, 1e-30f}, {3e20f, -0.0f, 7}, {0.1f, 0.2f, 0.3f});
  s.Add({5, 5, 5}, {6, 5, 5}, {5, 6, 5.5f});
  return s;
}

void ExpectSameSoup(const TriangleSoup& a, const TriangleSoup& b) {
  ASSERT_EQ(a.v.size(), b.v.size());
  for (size_t i = 0; i < a.v.size(); ++i) {
    EXPECT_EQ(a.v[i], b.v[i]) << "vertex " << i;
    EXPECT_EQ(std::signbit(a.v[i].y), std::signbit(b.v[i].y)) << "vertex " << i;
  }
}

void ExpectErrorNaming(const absl::StatusOr<TriangleSoup>& soup, const std::string& path,
                       absl::string_view reason) {
  ASSERT_FALSE(soup.ok());
  EXPECT_NE(soup.status().message().find(path), absl::string_view::npos) << soup.status();
  EXPECT_NE(soup.status().message().find(reason), absl::string_view::npos) << soup.status();
}

TEST(SoupCache, RoundTripIsExact) {
  const std::string path = TmpPath("round.tris");
  const TriangleSoup soup = ThreeTriangles();
  ASSERT_TRUE(WriteSoupCache(path, soup).ok());
  EXPECT_EQ(std::filesystem::file_size(path), 16u + 3 * 36 + 8);
  absl::StatusOr<TriangleSoup> back = ReadSoupCache(path);
  ASSERT_TRUE(back.ok()) << back.status();
  ExpectSameSoup(*back, soup);

  ASSERT_TRUE(WriteSoupCache(path, TriangleSoup()).ok());  // overwrite, empty soup
  back = ReadSoupCache(path);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_TRUE(back->empty());
}

TEST(SoupCache, FormatHasMagicCountAndWordFnvChecksum) {
  const std::string path = TmpPath("format.tris");
  TriangleSoup soup;
  soup.Add({1, 2, 3}, {4, 5, 6}, {7, 8, 9});
  ASSERT_TRUE(WriteSoupCache(path, soup).ok());
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  unsigned char bytes[16 + 36 + 8];
  ASSERT_EQ(std::fread(bytes, 1, sizeof(bytes), f), sizeof(bytes));
  std::fclose(f);
  EXPECT_EQ(std::string(reinterpret_cast<char*>(bytes), 8), "KDTRIS01");
  EXPECT_EQ(bytes[8], 1);
  uint64_t stored = 0;
  for (int i = 7; i >= 0; --i) stored = (stored << 8) | bytes[16 + 36 + i];
  EXPECT_EQ(stored, SoupChecksum(bytes + 8, 8 + 36));
}

TEST(SoupCache, TruncatedFileIsAnErrorNamingIt) {
  const std::string path = TmpPath("truncated.tris");
  ASSERT_TRUE(WriteSoupCache(path, ThreeTriangles()).ok());
  std::filesystem::resize_file(path, 16 + 2 * 36 + 8);
  ExpectErrorNaming(ReadSoupCache(path), path, "truncated");
  std::filesystem::resize_file(path, 5);
  ExpectErrorNaming(ReadSoupCache(path), path, "truncated");
}

TEST(SoupCache, CorruptionIsDetectedByTheChecksum) {
  const std::string path = TmpPath("corrupt.tris");
  ASSERT_TRUE(WriteSoupCache(path, ThreeTriangles()).ok());
  FlipByte(path, 16 + 40);  // a coordinate
  ExpectErrorNaming(ReadSoupCache(path), path, "checksum");
  ASSERT_TRUE(WriteSoupCache(path, ThreeTriangles()).ok());
  FlipByte(path, 16 + 3 * 36 + 3);  // the checksum itself
  ExpectErrorNaming(ReadSoupCache(path), path, "checksum");
}

TEST(SoupCache, WrongMagicAndMissingFileAreErrors) {
  const std::string path = TmpPath("magic.tris");
  ASSERT_TRUE(WriteSoupCache(path, ThreeTriangles()).ok());
  FlipByte(path, 7);
  ExpectErrorNaming(ReadSoupCache(path), path, "magic");
  WriteText(path, "this is not a cache file at all, just some text");
  ExpectErrorNaming(ReadSoupCache(path), path, "magic");
  const std::string missing = TmpPath("missing.tris");
  ExpectErrorNaming(ReadSoupCache(missing), missing, "cannot open");
  ExpectErrorNaming(ReadSoupCache(TmpPath("")), TmpPath(""), "");
}

TEST(SoupCache, WriteIntoMissingDirectoryIsAnError) {
  const std::string path = TmpPath("no/such/dir/x.tris");
  absl::Status s = WriteSoupCache(path, ThreeTriangles());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find(path), absl::string_view::npos) << s;
}

TEST(LoadMeshCached, SecondLoadComesFromTheCacheAndIsIdentical) {
  const std::string mesh = TmpPath("cached.obj");
  WriteText(mesh, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 1 2 5\nl 1 2\n");
  const std::string dir = TmpPath("cache_dir/nested");
  std::filesystem::remove_all(TmpPath("cache_dir"));

  LoadReport first;
  absl::StatusOr<TriangleSoup> a = LoadMeshCached(mesh, dir, &first);
  ASSERT_TRUE(a.ok()) << a.status();
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(first.cache_warning.empty()) << first.cache_warning;
  EXPECT_EQ(first.triangles, 2u);
  EXPECT_EQ(first.skipped_faces, 1u);
  EXPECT_EQ(first.dropped_degenerate, 1u);

  absl::StatusOr<std::string> cache_path = SoupCachePath(mesh, dir);
  ASSERT_TRUE(cache_path.ok()) << cache_path.status();
  EXPECT_TRUE(std::filesystem::exists(*cache_path));

  LoadReport second;
  absl::StatusOr<TriangleSoup> b = LoadMeshCached(mesh, dir, &second);
  ASSERT_TRUE(b.ok()) << b.status();
  EXPECT_TRUE(second.from_cache);
  ExpectSameSoup(*a, *b);
  EXPECT_EQ(second.triangles, first.triangles);
  EXPECT_EQ(second.skipped_faces, first.skipped_faces);
  EXPECT_EQ(second.dropped_degenerate, first.dropped_degenerate);
  EXPECT_EQ(second.dropped_nonfinite, first.dropped_nonfinite);

  // A corrupt entry is rebuilt, with a warning, not an error.
  FlipByte(*cache_path, 20);
  LoadReport third;
  absl::StatusOr<TriangleSoup> c = LoadMeshCached(mesh, dir, &third);
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_FALSE(third.from_cache);
  EXPECT_NE(third.cache_warning.find("checksum"), std::string::npos) << third.cache_warning;
  ExpectSameSoup(*a, *c);
  EXPECT_TRUE(ReadSoupCache(*cache_path).ok());
}

TEST(LoadMeshCached, ChangedMeshGetsANewKeyAndLoadOptionsArePartOfIt) {
  const std::string mesh = TmpPath("changing.obj");
  const std::string dir = TmpPath("cache_changing");
  WriteText(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_TRUE(LoadMeshCached(mesh, dir).ok());
  const std::string old_key = *SoupCachePath(mesh, dir);
  WriteText(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n");
  EXPECT_NE(*SoupCachePath(mesh, dir), old_key);
  LoadReport report;
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(mesh, dir, &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_FALSE(report.from_cache);
  EXPECT_EQ(soup->size(), 2u);
  LoadOptions keep;
  keep.drop_degenerate = false;
  EXPECT_NE(*SoupCachePath(mesh, dir, keep), *SoupCachePath(mesh, dir));
}

TEST(LoadMeshCached, ErrorsAndNoCacheDir) {
  const std::string missing = TmpPath("missing_mesh.obj");
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(missing, TmpPath("c"));
  ASSERT_FALSE(soup.ok());
  EXPECT_NE(soup.status().message().find(missing), absl::string_view::npos) << soup.status();
  const std::string mesh = TmpPath("nocache.obj");
  WriteText(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  LoadReport report;
  soup = LoadMeshCached(mesh, "", &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_FALSE(report.from_cache);
  EXPECT_EQ(soup->size(), 1u);
}

}  // namespace
}  // namespace kdtree
