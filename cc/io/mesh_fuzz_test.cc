// Smoke run of the mesh fuzz case (mesh_fuzz.h): seeded mutations (byte
// flips, cuts, repeated chunks, inserted tokens) of small good OBJ, OFF and
// PLY files (ASCII and both binary endiannesses). The long run is the
// libFuzzer target mesh_fuzzer.cc (command in its header).
#include "cc/io/mesh_fuzz.h"

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::string TmpDir() {
  const char* dir = std::getenv("TEST_TMPDIR");
  return dir != nullptr ? dir : "/tmp";
}

std::string BinaryPly(bool big) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](const void* p) {
    const char* c = static_cast<const char*>(p);
    for (int i = 0; i < 4; ++i) s.push_back(c[big ? 3 - i : i]);
  };
  const float v[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  for (const float& f : v) put(&f);
  const int32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& face : faces) {
    s.push_back(3);
    for (const int32_t& i : face) put(&i);
  }
  return s;
}

// Seeds: selector byte (0 obj, 1 off, 2 ply, 3 obj gzipped by the case,
// 4 bytes under a .ply.gz name) + file.
std::vector<std::string> Seeds() {
  return {
      std::string(1, '\0') + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -4 -2 -1\n",
      std::string(1, '\1') + "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3\n",
      std::string(1, '\2') +
          "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
          "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
          "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
      std::string(1, '\2') + BinaryPly(false),
      std::string(1, '\2') + BinaryPly(true),
      std::string(1, '\3') + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
      std::string(1, '\4') + std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03", 10) + "junk",
  };
}

std::string Mutate(std::string s, std::mt19937* rng) {
  static const char* const kTokens[] = {"-1", "0", "4294967295", "nan", "inf", "1e39", "\n",
                                        " ", "f ", "v ", "#", "/", "element face 9\n",
                                        "binary_big_endian", "end_header\n", "\xff\xff\xff\xff"};
  const int edits = 1 + (*rng)() % 4;
  for (int e = 0; e < edits && s.size() > 1; ++e) {
    const size_t pos = 1 + (*rng)() % (s.size() - 1);  // keep the selector
    switch ((*rng)() % 4) {
      case 0:
        s[pos] = static_cast<char>((*rng)());
        break;
      case 1:
        s.resize(pos);
        break;
      case 2:
        s.insert(pos, s.substr(pos, (*rng)() % 16));
        break;
      default:
        s.insert(pos, kTokens[(*rng)() % (sizeof(kTokens) / sizeof(kTokens[0]))]);
    }
  }
  return s;
}

TEST(MeshFuzz, SeedsLoad) {
  for (const std::string& s : Seeds()) {
    // (the truncated gzip seed is refused by name: also 0)
    EXPECT_EQ(MeshFuzzCase(reinterpret_cast<const uint8_t*>(s.data()), s.size(), TmpDir()), 0u);
  }
}

TEST(MeshFuzz, MutatedFilesKeepEveryPromise) {
  std::mt19937 rng(6);
  const std::vector<std::string> seeds = Seeds();
  size_t broken = 0;
  for (int i = 0; i < 1500; ++i) {
    const std::string s = Mutate(seeds[i % seeds.size()], &rng);
    broken += MeshFuzzCase(reinterpret_cast<const uint8_t*>(s.data()), s.size(), TmpDir());
  }
  EXPECT_EQ(broken, 0u);
}

TEST(MeshFuzz, EmptyAndSelectorOnly) {
  EXPECT_EQ(MeshFuzzCase(nullptr, 0, TmpDir()), 0u);
  const uint8_t one[] = {1};
  EXPECT_EQ(MeshFuzzCase(one, 1, TmpDir()), 0u);
}

}  // namespace
}  // namespace kdtree
