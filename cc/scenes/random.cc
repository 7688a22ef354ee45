#include "cc/scenes/random.h"

#include <cmath>

namespace kdtree {
namespace scenes {
namespace {

float Smooth(float t) { return t * t * (3.0f - 2.0f * t); }
float Lerp(float a, float b, float t) { return a + (b - a) * t; }

}  // namespace

float ValueNoise2(uint64_t seed, float x, float z, float cell) {
  const float fx = x / cell, fz = z / cell;
  const float flx = std::floor(fx), flz = std::floor(fz);
  const int64_t ix = static_cast<int64_t>(flx), iz = static_cast<int64_t>(flz);
  const float tx = Smooth(fx - flx), tz = Smooth(fz - flz);
  const float a = ToUnit(Hash(seed, ix, iz)), b = ToUnit(Hash(seed, ix + 1, iz));
  const float c = ToUnit(Hash(seed, ix, iz + 1)), d = ToUnit(Hash(seed, ix + 1, iz + 1));
  return Lerp(Lerp(a, b, tx), Lerp(c, d, tx), tz);
}

float ValueNoise3(uint64_t seed, float x, float y, float z, float cell) {
  const float f[3] = {x / cell, y / cell, z / cell};
  int64_t i[3];
  float t[3];
  for (int k = 0; k < 3; ++k) {
    const float fl = std::floor(f[k]);
    i[k] = static_cast<int64_t>(fl);
    t[k] = Smooth(f[k] - fl);
  }
  float corner[8];
  for (int c = 0; c < 8; ++c) {
    corner[c] = ToUnit(Hash(seed, i[0] + (c & 1), i[1] + ((c >> 1) & 1), i[2] + ((c >> 2) & 1)));
  }
  const float x00 = Lerp(corner[0], corner[1], t[0]), x10 = Lerp(corner[2], corner[3], t[0]);
  const float x01 = Lerp(corner[4], corner[5], t[0]), x11 = Lerp(corner[6], corner[7], t[0]);
  return Lerp(Lerp(x00, x10, t[1]), Lerp(x01, x11, t[1]), t[2]);
}

float Fbm2(uint64_t seed, float x, float z, float cell, int octaves) {
  float sum = 0, weight = 0, amplitude = 1;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * ValueNoise2(seed + 7919 * o, x, z, cell);
    weight += amplitude;
    amplitude *= 0.5f;
    cell *= 0.5f;
  }
  return sum / weight;
}

}  // namespace scenes
}  // namespace kdtree
