#include "cc/io/mesh_loader.h"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "absl/strings/string_view.h"
#include "cc/geometry/triangle.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TmpPath(const std::string& name) {
  const char* dir = std::getenv("TEST_TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/" + name;
}

std::string WriteFile(const std::string& name, absl::string_view bytes) {
  const std::string path = TmpPath(name);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  EXPECT_NE(f, nullptr) << path;
  if (f == nullptr) return path;
  EXPECT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
  std::fclose(f);
  return path;
}

std::string WriteGzip(const std::string& name, absl::string_view bytes) {
  const std::string path = TmpPath(name);
  gzFile gz = gzopen(path.c_str(), "wb");
  EXPECT_NE(gz, nullptr) << path;
  if (gz == nullptr) return path;
  EXPECT_EQ(gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size())),
            static_cast<int>(bytes.size()));
  gzclose(gz);
  return path;
}

std::string ReadBytes(const std::string& path) {
  std::string out;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return out;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) out.append(buf, n);
  std::fclose(f);
  return out;
}

// Binary little-endian PLY with float vertices and int triangle indices.
std::string BinaryPly(const std::vector<Vec3>& verts, const std::vector<std::vector<int>>& faces) {
  std::string s = absl::StrFormat(
      "ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
      "property float y\nproperty float z\nelement face %d\n"
      "property list uchar int vertex_indices\nend_header\n",
      verts.size(), faces.size());
  for (const Vec3& v : verts) s.append(reinterpret_cast<const char*>(&v), sizeof(v));
  for (const auto& f : faces) {
    s.push_back(static_cast<char>(f.size()));
    for (int32_t i : f) s.append(reinterpret_cast<const char*>(&i), 4);
  }
  return s;
}

constexpr char kAsciiPly[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

double TotalArea(const TriangleSoup& s) {
  double area = 0;
  for (size_t i = 0; i < s.size(); ++i) area += 0.5 * Length(Cross(s.b(i) - s.a(i), s.c(i) - s.a(i)));
  return area;
}

void ExpectUnitSquare(const absl::StatusOr<TriangleSoup>& soup) {
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 2u);
  EXPECT_DOUBLE_EQ(TotalArea(*soup), 1.0);
  EXPECT_EQ(soup->Bounds().lo, Vec3(0, 0, 0));
  EXPECT_EQ(soup->Bounds().hi, Vec3(1, 1, 0));
}

void ExpectErrorNaming(const absl::StatusOr<TriangleSoup>& soup, const std::string& path) {
  ASSERT_FALSE(soup.ok());
  EXPECT_NE(soup.status().message().find(path), absl::string_view::npos) << soup.status();
}

TEST(LoadMesh, ObjQuadIsTriangulatedIntoTwoTriangles) {
  const std::string path =
      WriteFile("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  LoadReport report;
  absl::StatusOr<TriangleSoup> soup = LoadMesh(path, &report);
  ExpectUnitSquare(soup);
  EXPECT_EQ(report.triangles, 2u);
  EXPECT_EQ(report.skipped_faces, 0u);
  EXPECT_EQ(report.dropped_degenerate, 0u);
  EXPECT_EQ(report.dropped_nonfinite, 0u);
  EXPECT_GE(report.load_seconds, 0.0);
}

TEST(LoadMesh, ReadsAsciiPly) { ExpectUnitSquare(LoadMesh(WriteFile("ascii.ply", kAsciiPly))); }

TEST(LoadMesh, ReadsBinaryPlyKeepingFaceOrder) {
  const std::vector<Vec3> verts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  absl::StatusOr<TriangleSoup> soup =
      LoadMesh(WriteFile("binary.ply", BinaryPly(verts, {{0, 1, 2}, {0, 2, 3}})));
  ExpectUnitSquare(soup);
  ASSERT_TRUE(soup.ok());
  EXPECT_EQ(soup->a(0), verts[0]);
  EXPECT_EQ(soup->b(0), verts[1]);
  EXPECT_EQ(soup->c(0), verts[2]);
  EXPECT_EQ(soup->c(1), verts[3]);
}

TEST(LoadMesh, ReadsOff) {
  ExpectUnitSquare(LoadMesh(
      WriteFile("square.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")));
}

TEST(LoadMesh, AppliesNodeTransformsOfGltf) {
  // One triangle (0,0,0) (1,0,0) (0,1,0) in a node translated by (10, 0, 0).
  const std::string path = WriteFile(
      "moved.gltf",
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"translation":[10,0,0]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]})");
  absl::StatusOr<TriangleSoup> soup = LoadMesh(path);
  ASSERT_TRUE(soup.ok()) << soup.status();
  ASSERT_EQ(soup->size(), 1u);
  EXPECT_EQ(soup->Bounds().lo, Vec3(10, 0, 0));
  EXPECT_EQ(soup->Bounds().hi, Vec3(11, 1, 0));
}

TEST(LoadMesh, ReadsGzipCompressedFilesWithInnerExtensionAsHint) {
  ExpectUnitSquare(LoadMesh(WriteGzip("square.ply.gz", kAsciiPly)));
  ExpectUnitSquare(
      LoadMesh(WriteGzip("quad.OBJ.GZ", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")));
}

TEST(LoadMesh, CorruptOrTruncatedGzipIsAnError) {
  const std::string good = ReadBytes(WriteGzip("whole.ply.gz", kAsciiPly));
  ASSERT_GT(good.size(), 20u);
  const std::string cut = WriteFile("cut.ply.gz", good.substr(0, good.size() / 2));
  ExpectErrorNaming(LoadMesh(cut), cut);
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x5a;
  flipped[good.size() - 6] ^= 0x5a;  // inside the CRC trailer
  const std::string bad = WriteFile("flipped.ply.gz", flipped);
  ExpectErrorNaming(LoadMesh(bad), bad);
  const std::string plain = WriteFile("plain.ply.gz", kAsciiPly);
  ExpectErrorNaming(LoadMesh(plain), plain);
}

TEST(LoadMesh, NonFiniteAndAbsurdTrianglesAreDroppedAndCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Vec3> verts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {nan, 0, 1}};
  LoadReport report;
  absl::StatusOr<TriangleSoup> soup =
      LoadMesh(WriteFile("nan.ply", BinaryPly(verts, {{0, 1, 2}, {0, 1, 3}, {3, 2, 1}})), &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 1u);
  EXPECT_EQ(report.triangles, 1u);
  EXPECT_EQ(report.dropped_nonfinite, 2u);

  soup = LoadMesh(WriteFile("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1e31\nv inf 0 0\n"
                                        "f 1 2 3\nf 1 2 4\nf 5 1 2\n"),
                  &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 1u);
  EXPECT_EQ(report.dropped_nonfinite, 2u);
  for (const Vec3& p : soup->v) EXPECT_TRUE(IsFinite(p));
}

TEST(LoadMesh, DegenerateTrianglesAreDroppedAndCounted) {
  const std::string path = WriteFile(
      "degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 3 3 3\nv 6 6 6\n"
                        "f 1 2 3\nf 1 2 4\nf 1 1 3\nf 1 5 6\n");
  LoadReport report;
  absl::StatusOr<TriangleSoup> soup = LoadMesh(path, &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 1u);
  EXPECT_EQ(report.dropped_degenerate, 3u);

  LoadOptions keep;
  keep.drop_degenerate = false;
  soup = LoadMesh(path, &report, keep);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 4u);
  EXPECT_EQ(report.dropped_degenerate, 0u);
}

TEST(LoadMesh, PointAndLineFacesAreSkippedAndCounted) {
  LoadReport report;
  absl::StatusOr<TriangleSoup> soup = LoadMesh(
      WriteFile("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\np 3\n"), &report);
  ASSERT_TRUE(soup.ok()) << soup.status();
  EXPECT_EQ(soup->size(), 1u);
  EXPECT_EQ(report.skipped_faces, 2u);
}

TEST(IsDegenerateTriangle, ExactOnFloatInputs) {
  EXPECT_FALSE(IsDegenerateTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_TRUE(IsDegenerateTriangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  EXPECT_TRUE(IsDegenerateTriangle({1, 2, 3}, {1, 2, 3}, {4, 5, 6}));
  EXPECT_TRUE(IsDegenerateTriangle({1e-30f, 0, 0}, {1e20f, 0, 0}, {-1e30f, 0, 0}));
  // One float ulp off the line is not degenerate, however thin.
  EXPECT_FALSE(IsDegenerateTriangle({0, 0, 0}, {1, 1, 0}, {2, std::nextafter(2.0f, 3.0f), 0}));
  EXPECT_FALSE(IsDegenerateTriangle({1e20f, 0, 0}, {1e20f, 1e-20f, 0}, {0, 0, 1e-30f}));
}

TEST(LoadMesh, EmptyFileAndFileWithoutFacesAreErrorsNamingTheFile) {
  const std::string empty = WriteFile("empty.obj", "");
  ExpectErrorNaming(LoadMesh(empty), empty);
  const std::string no_faces = WriteFile("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  ExpectErrorNaming(LoadMesh(no_faces), no_faces);
  const std::string points = WriteFile("points.ply", BinaryPly({{0, 0, 0}, {1, 0, 0}}, {}));
  ExpectErrorNaming(LoadMesh(points), points);
  const std::string only_lines = WriteFile("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  ExpectErrorNaming(LoadMesh(only_lines), only_lines);
}

TEST(LoadMesh, MissingFileAndDirectoryAreErrorsNamingThem) {
  const std::string missing = TmpPath("does_not_exist.obj");
  absl::StatusOr<TriangleSoup> soup = LoadMesh(missing);
  ExpectErrorNaming(soup, missing);
  EXPECT_EQ(soup.status().code(), absl::StatusCode::kNotFound);
  ExpectErrorNaming(LoadMesh(TmpPath("")), TmpPath(""));
  EXPECT_FALSE(LoadMesh("").ok());
}

TEST(LoadMesh, GarbageBytesAreAnErrorNotACrash) {
  std::mt19937 rng(12345);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = static_cast<char>(rng());
  for (const char* ext : {"ply", "obj", "off", "stl", "glb", "gltf", "3ds", "ac", "blend"}) {
    const std::string path = WriteFile(std::string("garbage.") + ext, garbage);
    absl::StatusOr<TriangleSoup> soup = LoadMesh(path);
    if (soup.ok()) {  // a lenient reader may find something; it must be sane
      for (size_t i = 0; i < soup->size(); ++i) {
        EXPECT_TRUE(IsSaneTriangle(soup->a(i), soup->b(i), soup->c(i)));
      }
    } else {
      EXPECT_NE(soup.status().message().find(path), absl::string_view::npos) << soup.status();
    }
  }
  const std::string ply = WriteFile("garbage2.ply", "ply\n" + garbage);
  ExpectErrorNaming(LoadMesh(ply), ply);
}

TEST(LoadMesh, TruncatedBinaryPlyIsAnErrorOrShorterNotACrash) {
  std::vector<Vec3> verts;
  std::vector<std::vector<int>> faces;
  for (int i = 0; i < 100; ++i) {
    verts.push_back(Vec3(static_cast<float>(i), 0, 0));
    verts.push_back(Vec3(static_cast<float>(i), 1, 0));
    verts.push_back(Vec3(static_cast<float>(i), 0, 1));
    faces.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  const std::string whole = BinaryPly(verts, faces);
  for (size_t cut : {whole.size() - 7, whole.size() - 13 * 50, whole.size() / 2, size_t{300}}) {
    const std::string path = WriteFile("truncated.ply", whole.substr(0, cut));
    absl::StatusOr<TriangleSoup> soup = LoadMesh(path);
    if (soup.ok()) {
      EXPECT_LE(soup->size(), faces.size());
    } else {
      EXPECT_NE(soup.status().message().find(path), absl::string_view::npos) << soup.status();
    }
  }
}

}  // namespace
}  // namespace kdtree
