// Smoke run of the environment-file fuzz case (env_file_fuzz.h): every
// preset's file, mutated by seeded token swaps, cuts and byte flips. The long
// run is the libFuzzer target env_file_fuzzer.cc (command in its header).
#include "cc/robust/env_file_fuzz.h"

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

size_t ParseBytes(const std::string& s) {
  return EnvFileFuzzCase(reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

TEST(EnvFileFuzz, PresetFilesKeepEveryPromise) {
  for (const std::string& name : PresetNames()) EXPECT_EQ(ParseBytes(Preset(name)->ToEnvironment()), 0u);
}

TEST(EnvFileFuzz, MutatedFilesKeepEveryPromise) {
  static const char* const kTokens[] = {
      "{", "}", "#", "//", "\n", " ", "KDTree", "RTCore", "Binning", "maxDepth", "bins",
      "useClipping", "ON", "OFF", "-1", "0", "61", "99999999999", "\xff", "\0"};
  std::vector<std::string> seeds;
  for (const std::string& name : PresetNames()) seeds.push_back(Preset(name)->ToEnvironment());
  std::mt19937 rng(9);
  size_t broken = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string s = seeds[i % seeds.size()];
    const int edits = 1 + rng() % 4;
    for (int e = 0; e < edits && !s.empty(); ++e) {
      const size_t pos = rng() % s.size();
      switch (rng() % 4) {
        case 0:
          s[pos] = static_cast<char>(rng());
          break;
        case 1:
          s.resize(pos);
          break;
        case 2:
          s.erase(pos, rng() % 8);
          break;
        default:
          s.insert(pos, kTokens[rng() % (sizeof(kTokens) / sizeof(kTokens[0]))]);
      }
    }
    broken += ParseBytes(s);
  }
  EXPECT_EQ(broken, 0u);
}

TEST(EnvFileFuzz, EmptyAndBinaryInputs) {
  EXPECT_EQ(EnvFileFuzzCase(nullptr, 0), 0u);
  const std::string zeros(64, '\0');
  EXPECT_EQ(ParseBytes(zeros), 0u);
  EXPECT_EQ(ParseBytes(std::string(1000, '{')), 0u);
  EXPECT_EQ(ParseBytes(std::string(1000, '}')), 0u);
}

}  // namespace
}  // namespace kdtree
