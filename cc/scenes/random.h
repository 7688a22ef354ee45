// Deterministic randomness for the scene generators.
//
// Only integer arithmetic decides the random numbers (no <random>
// distributions, whose output differs between standard libraries), so the same
// seed gives the same mesh with any compiler flags on the same machine.
#ifndef KDTREE_CC_SCENES_RANDOM_H_
#define KDTREE_CC_SCENES_RANDOM_H_

#include <cstdint>

#include "cc/base/mix64.h"

namespace kdtree {
namespace scenes {

using kdtree::Mix64;  // cc/base/mix64.h

// Hash of a seed and integer lattice coordinates.
inline uint64_t Hash(uint64_t seed, int64_t x, int64_t y = 0, int64_t z = 0) {
  uint64_t h = Mix64(seed);
  h = Mix64(h ^ static_cast<uint64_t>(x));
  h = Mix64(h ^ static_cast<uint64_t>(y));
  return Mix64(h ^ static_cast<uint64_t>(z));
}

// Uniform float in [0, 1) from the top 24 bits of a hash (exact in float).
inline float ToUnit(uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }

// xoshiro256** seeded through SplitMix64.
class Rng {
 public:
  explicit Rng(uint64_t seed) {
    for (int i = 0; i < 4; ++i) s_[i] = Mix64(seed + 0x632be59bd9b4e019ULL * i);
  }

  uint64_t Next() {
    const uint64_t result = Rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = Rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1).
  float Uniform() { return ToUnit(Next()); }
  // Uniform in [lo, hi).
  float Uniform(float lo, float hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [0, n), n > 0 (tiny modulo bias is irrelevant here).
  int64_t UniformInt(int64_t n) { return static_cast<int64_t>(Next() % static_cast<uint64_t>(n)); }

 private:
  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t s_[4];
};

// Smooth value noise in [0, 1) on the integer lattice scaled by 1 / `cell`.
float ValueNoise2(uint64_t seed, float x, float z, float cell);
float ValueNoise3(uint64_t seed, float x, float y, float z, float cell);
// Fractal sum of `octaves` value-noise octaves (cell halves each octave), in [0, 1).
float Fbm2(uint64_t seed, float x, float z, float cell, int octaves);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_RANDOM_H_
