// Binary dump of every traced ray and its result, so that any other tracer can
// be checked against this one ray by ray (a Python reader is a few lines of
// numpy: np.dtype below).
//
// File format, all little-endian:
//   bytes [0, 8)       magic "KDRAYS01"
//   bytes [8, 12)      uint32 record size, 56
//   bytes [12, 16)     uint32 image width
//   bytes [16, 20)     uint32 image height
//   bytes [20, 24)     uint32 reserved, 0
//   bytes [24, 32)     uint64 record count n
//   bytes [32, 32+56n) n records (RayRecord, ray_record.h):
//      0 float32[3] origin      12 float32[3] dir (unit length, except shadow rays:
//                                  light - origin, with tmax = 1)
//     24 float32 tmin          28 float32 tmax     (hits count for tmin < t <= tmax)
//     32 uint8 kind (0 primary closest hit, 1 shadow any hit, 2 ambient-occlusion any hit)
//     33 uint8 hit (1 = hit / occluded)
//     34 uint16 light index (shadow), sample index (ao), 0 (primary)
//     36 uint32 pixel = y * width + x of the primary ray, row 0 at the top
//     40 uint32 triangle index (primary hit), 0xffffffff otherwise
//     44 float32 t   48 float32 u   52 float32 v   (primary hit; 0 otherwise)
//   last 8 bytes       uint64 checksum of bytes [8, 32 + 56n): FNV-1a over
//                      little-endian 64-bit words (h = 0xcbf29ce484222325;
//                      h = (h ^ w) * 0x100000001b3 per word), the same rule as
//                      the triangle cache (cc/io/soup_cache.h).
// Records are in the renderer's order (renderer.h): primary rays by pixel,
// then shadow rays by pixel and light, then AO rays by pixel and sample.
// numpy: np.dtype([('o','<f4',3),('d','<f4',3),('tmin','<f4'),('tmax','<f4'),
//   ('kind','u1'),('hit','u1'),('index','<u2'),('pixel','<u4'),('tri','<u4'),
//   ('t','<f4'),('u','<f4'),('v','<f4')]), records at offset 32.
#ifndef KDTREE_CC_RENDER_RAY_DUMP_H_
#define KDTREE_CC_RENDER_RAY_DUMP_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "cc/render/ray_record.h"

namespace kdtree {

struct RayDump {
  int width = 0;
  int height = 0;
  std::vector<RayRecord> records;
};

// Writes atomically (a temporary file beside `path`, then rename). Errors name
// the file.
absl::Status WriteRayDump(const std::string& path, const RayDump& dump);

// Reads a dump; wrong magic or record size, truncation, trailing bytes, a
// checksum mismatch or an invalid kind are errors naming the file.
absl::StatusOr<RayDump> ReadRayDump(const std::string& path);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_RAY_DUMP_H_
