#include "cc/scenes/spm.h"

#include <cstdint>
#include <string>

#include "absl/strings/match.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/spm_testing.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

Mesh Quad(float z) {
  Mesh m;
  m.AddVertex({0, 0, z});
  m.AddVertex({1, 0, z});
  m.AddVertex({1, 1, z});
  m.AddVertex({0, 1, z});
  m.AddQuad(0, 1, 2, 3);
  return m;
}

// A strip of `n` vertices (n - 2 triangles) in the unit square.
Mesh Strip(int n) {
  Mesh m;
  for (int i = 0; i < n; ++i) {
    m.AddVertex({static_cast<float>(i) / n, static_cast<float>(i % 2), 0.5f});
  }
  for (int i = 2; i < n; ++i) m.AddTriangle(i - 2, i - 1, i);
  return m;
}

std::string Status(const absl::StatusOr<Mesh>& m) { return m.status().ToString(); }

TEST(Spm, ReadsPositionsAndTriangles) {
  SpmInfo info;
  absl::StatusOr<Mesh> m = ParseSpm(EncodeSpm(Quad(2)), "quad.spm", {}, &info);
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->vertices, Quad(2).vertices);
  EXPECT_EQ(m->faces, Quad(2).faces);
  EXPECT_FALSE(info.skinned);
  EXPECT_EQ(info.materials, 1);
  EXPECT_EQ(info.sections, 1);
  EXPECT_EQ(info.buffers, 1);
  EXPECT_EQ(info.trailing_bytes, 0u);
  EXPECT_EQ(info.header_bounds.hi, Vec3(1, 1, 2));
}

TEST(Spm, SkipsEveryOptionalAttributeAndConcatenatesBuffers) {
  SpmWriteOptions o;
  o.skinned = true;
  o.normals = true;
  o.colors = true;
  o.tangents = true;
  o.materials = {{"", ""}, {"a.png", ""}, {"b.png", "b_lightmap.png"}};
  o.trailer = "armature bytes, not read";
  std::vector<std::vector<SpmTestBuffer>> sections(2);
  sections[0].push_back({Quad(0), 0});
  sections[0].push_back({Quad(1), 1});
  sections[1].push_back({Quad(2), 2});
  SpmInfo info;
  absl::StatusOr<Mesh> m = ParseSpm(EncodeSpm(o, sections), "all.spm", {}, &info);
  ASSERT_TRUE(m.ok()) << m.status();
  Mesh want = Quad(0);
  want.Append(Quad(1));
  want.Append(Quad(2));
  EXPECT_EQ(m->vertices, want.vertices);
  EXPECT_EQ(m->faces, want.faces);
  EXPECT_TRUE(info.skinned && info.normals && info.colors && info.tangents);
  EXPECT_EQ(info.sections, 2);
  EXPECT_EQ(info.buffers, 3);
  EXPECT_EQ(info.trailing_bytes, o.trailer.size());
}

TEST(Spm, SixteenBitIndicesFrom256Vertices) {
  for (int n : {255, 256, 1000}) {
    absl::StatusOr<Mesh> m = ParseSpm(EncodeSpm(Strip(n)), "strip.spm");
    ASSERT_TRUE(m.ok()) << n << ": " << m.status();
    EXPECT_EQ(m->faces, Strip(n).faces) << n;
  }
}

TEST(Spm, EveryTruncationIsAnErrorNamingTheFile) {
  SpmWriteOptions o;
  o.normals = o.colors = o.tangents = true;
  o.materials = {{"t.png", "u.png"}};
  const std::string bytes = EncodeSpm(o, {{{Strip(300), 0}}});
  ASSERT_TRUE(ParseSpm(bytes, "cut.spm").ok());
  for (size_t n = 0; n < bytes.size(); ++n) {
    absl::StatusOr<Mesh> m = ParseSpm(bytes.substr(0, n), "cut.spm");
    ASSERT_FALSE(m.ok()) << n;
    EXPECT_TRUE(absl::StartsWith(m.status().message(), "cut.spm: truncated")) << Status(m);
  }
}

TEST(Spm, RejectsMalformedHeaders) {
  const std::string good = EncodeSpm(Quad(0));
  struct Case {
    size_t offset;
    char byte;
    const char* reason;
  } cases[] = {
      {0, 'X', "no 'SP' magic"},
      {2, static_cast<char>(2 << 3 | 2), "unsupported version 2"},
      {2, static_cast<char>(1 << 3 | 5), "unknown mesh type 5"},
      {3, 0x10, "unknown vertex flags"},
  };
  for (const Case& c : cases) {
    std::string bad = good;
    bad[c.offset] = c.byte;
    absl::StatusOr<Mesh> m = ParseSpm(bad, "bad.spm");
    ASSERT_FALSE(m.ok()) << c.reason;
    EXPECT_TRUE(absl::StrContains(m.status().message(), c.reason)) << Status(m);
    EXPECT_TRUE(absl::StartsWith(m.status().message(), "bad.spm: ")) << Status(m);
  }
}

// Offset of the first buffer's header in a default one-material file.
constexpr size_t kBufferHeader = 4 + 24 + 2 + 2 + 2 + 2;

TEST(Spm, RejectsMalformedBuffers) {
  const std::string good = EncodeSpm(Quad(0));
  {
    std::string bad = good;
    bad[kBufferHeader + 8] = 1;  // material 1 of 1
    EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bad, "m.spm")), "material 1 of 1"));
  }
  {
    std::string bad = good;
    bad[kBufferHeader + 4] = 5;  // 5 indices
    EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bad, "m.spm")), "not a multiple of 3"));
  }
  {
    std::string bad = good;
    bad[bad.size() - 1] = 4;  // index 4 of 4 vertices
    EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bad, "m.spm")), "index 4 of triangle 1"));
  }
  {
    std::string bad = good;
    bad[kBufferHeader + 2] = 1;  // 65540 vertices
    EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bad, "m.spm")), "at most 65535"));
  }
  {
    std::string bad = good;
    bad[kBufferHeader + 10 + 3] = 0x7f;  // vertex 0 x = NaN-ish exponent
    bad[kBufferHeader + 10 + 2] = static_cast<char>(0xc0);
    EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bad, "m.spm")), "not finite"));
  }
}

TEST(Spm, StaticMeshMustEndWithItsLastBuffer) {
  const std::string bytes = EncodeSpm(Quad(0)) + "xyz";
  EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bytes, "t.spm")), "3 bytes after"));
  SpmOptions lenient;
  lenient.allow_trailing_bytes = true;
  EXPECT_TRUE(ParseSpm(bytes, "t.spm", lenient).ok());
}

TEST(Spm, VertexOutsideHeaderBoundsMeansAMisreadLayout) {
  std::string bytes = EncodeSpm(Quad(0));
  bytes[4 + 12 + 3] = 0x3e;  // header max x: 1.0 -> 0.25
  EXPECT_TRUE(absl::StrContains(Status(ParseSpm(bytes, "b.spm")), "outside the header's"));
  SpmOptions unchecked;
  unchecked.bounds_tolerance = -1;
  EXPECT_TRUE(ParseSpm(bytes, "b.spm", unchecked).ok());
}

TEST(Spm, CorruptedBytesNeverCrash) {
  SpmWriteOptions o;
  o.skinned = o.normals = o.colors = true;
  o.materials = {{"t.png", ""}, {"", ""}};
  const std::string good = EncodeSpm(o, {{{Strip(300), 0}, {Quad(1), 1}}});
  uint32_t state = 12345;
  int failures = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bad = good;
    for (int k = 0; k < 1 + trial % 4; ++k) {
      state = state * 1664525u + 1013904223u;
      bad[(state >> 8) % bad.size()] = static_cast<char>(state >> 24);
    }
    absl::StatusOr<Mesh> m = ParseSpm(bad, "fuzz.spm");
    if (!m.ok()) {
      ++failures;
      continue;
    }
    for (const Mesh::Face& f : m->faces) {
      for (int32_t i : f) ASSERT_LT(static_cast<size_t>(i), m->vertices.size());
    }
  }
  EXPECT_GT(failures, 0);
}

TEST(Spm, MissingFileIsNamed) {
  absl::StatusOr<Mesh> m = ReadSpm("/nonexistent/x.spm");
  EXPECT_EQ(m.status().code(), absl::StatusCode::kNotFound);
  EXPECT_TRUE(absl::StrContains(m.status().message(), "/nonexistent/x.spm"));
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
