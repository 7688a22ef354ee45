// Inputs that are not plain files, and inputs over the budget (issue 24): each
// is loaded once or refused by name, never hangs or inflates without bound.
#include "cc/io/mesh_input.h"

#include <sys/stat.h>
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "absl/strings/match.h"
#include "cc/io/mesh_loader.h"
#include "cc/io/soup_cache.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

constexpr char kQuad[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

std::string TmpPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/" + name;
}

std::string WriteFile(const std::string& name, const std::string& bytes) {
  const std::string path = TmpPath(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string Gzip(const std::string& name, const std::string& bytes, int members = 1) {
  const std::string path = TmpPath(name);
  std::remove(path.c_str());
  for (int m = 0; m < members; ++m) {
    gzFile gz = gzopen(path.c_str(), "ab");
    gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(gz);
  }
  return path;
}

// A named pipe whose writer sends `bytes` once; joined by the destructor.
struct Fifo {
  Fifo(const std::string& name, std::string bytes) : path(TmpPath(name)) {
    std::remove(path.c_str());
    EXPECT_EQ(mkfifo(path.c_str(), 0600), 0);
    writer = std::thread([p = path, b = std::move(bytes)] { std::ofstream(p, std::ios::binary) << b; });
  }
  ~Fifo() { writer.join(); }
  std::string path;
  std::thread writer;
};

void ExpectError(const absl::StatusOr<TriangleSoup>& soup, const std::string& path,
                 const std::string& why) {
  ASSERT_FALSE(soup.ok());
  EXPECT_TRUE(absl::StartsWith(soup.status().message(), path + ": ")) << soup.status();
  EXPECT_TRUE(absl::StrContains(soup.status().message(), why)) << soup.status();
}

TEST(MeshInput, ANamedPipeIsReadOnce) {
  Fifo fifo("quad_pipe.obj", kQuad);
  absl::StatusOr<TriangleSoup> soup = LoadMesh(fifo.path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 2u);
}

TEST(MeshInput, APipeWithoutExtensionIsRecognisedByItsBytes) {
  Fifo fifo("quad_pipe_noext", kQuad);  // as from bash's <(cat quad.obj)
  absl::StatusOr<TriangleSoup> soup = LoadMesh(fifo.path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 2u);
}

TEST(MeshInput, AGzipPipeIsInflated) {
  std::ifstream gz(Gzip("quad_for_pipe.obj.gz", kQuad), std::ios::binary);
  Fifo fifo("quad_pipe_gz", std::string(std::istreambuf_iterator<char>(gz), {}));
  absl::StatusOr<TriangleSoup> soup = LoadMesh(fifo.path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 2u);
}

TEST(MeshInput, APipeIsNeverCached) {
  const std::string cache = TmpPath("pipe_cache");
  for (int i = 0; i < 2; ++i) {
    // Two different meshes through the same pipe path: each is loaded.
    Fifo fifo("cached_pipe.obj", i == 0 ? kQuad : "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    LoadReport report;
    absl::StatusOr<TriangleSoup> soup = LoadMeshCached(fifo.path, cache, &report);
    ASSERT_TRUE(soup.ok()) << soup.status();
    EXPECT_EQ(soup->size(), i == 0 ? 2u : 1u);
    EXPECT_FALSE(report.from_cache);
  }
}

TEST(MeshInput, DirectoryAndDeviceAreRefusedByName) {
  ExpectError(LoadMesh(TmpPath("")), TmpPath(""), "is a directory");
  ExpectError(LoadMesh("/dev/zero"), "/dev/zero", "is a device");
}

TEST(MeshInput, AFileOverTheBudgetIsRefusedByItsSize) {
  const std::string path = WriteFile("over_budget.obj", kQuad);
  LoadOptions options;
  options.max_input_bytes = 10;
  ExpectError(LoadMesh(path, nullptr, options), path, "more than the input budget of 10 bytes");
}

TEST(MeshInput, AGzipBombStopsAtTheBudget) {
  // 64 MiB of blank lines inflate from about 64 KB; the budget is 1 MiB.
  const std::string path = Gzip("bomb.obj.gz", std::string(size_t{64} << 20, '\n'));
  LoadOptions options;
  options.max_input_bytes = size_t{1} << 20;
  ExpectError(LoadMesh(path, nullptr, options), path, "inflates to more than the input budget");
}

TEST(MeshInput, EveryGzipMemberIsRead) {
  const std::string path = Gzip("two_members.obj.gz", kQuad, 2);
  absl::StatusOr<TriangleSoup> soup = LoadMesh(path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 4u);
}

TEST(MeshInput, BytesAfterTheLastGzipMemberAreIgnored) {
  // As zlib's gzread does (some tools pad files with zeros).
  const std::string path = Gzip("padded.obj.gz", kQuad);
  std::ofstream(path, std::ios::binary | std::ios::app) << std::string(16, '\0');
  absl::StatusOr<TriangleSoup> soup = LoadMesh(path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 2u);
}

TEST(MeshInput, APipeOverTheBudgetIsRefusedWithTheBudget) {
  Fifo fifo("big_pipe.obj", kQuad);  // fits the pipe's buffer: the writer never blocks
  LoadOptions options;
  options.max_input_bytes = 10;
  absl::StatusOr<TriangleSoup> soup = LoadMesh(fifo.path, nullptr, options);
  ExpectError(soup, fifo.path, "is longer than the input budget of 10 bytes");
  EXPECT_EQ(soup.status().code(), absl::StatusCode::kResourceExhausted);
}

TEST(MeshInput, SniffsTheFormatsItKnows) {
  EXPECT_EQ(SniffMeshFormat("ply\nformat ascii 1.0\n"), "ply");
  EXPECT_EQ(SniffMeshFormat("OFF\n3 1 0\n"), "off");
  EXPECT_EQ(SniffMeshFormat("glTF\x02"), "glb");
  EXPECT_EQ(SniffMeshFormat("# made by hand\n\nv 0 0 0\n"), "obj");
  EXPECT_EQ(SniffMeshFormat("hello\n"), "");
  EXPECT_EQ(Extension("a/b.c/mesh.PLY"), "ply");
  EXPECT_EQ(Extension("a/b.c/mesh"), "");
}

}  // namespace
}  // namespace kdtree
