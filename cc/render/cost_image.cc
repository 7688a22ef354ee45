#include "cc/render/cost_image.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

#include "absl/strings/str_cat.h"

namespace kdtree {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the counts are written in host order as '<u4'");

uint32_t SaturatingAdd(uint32_t a, uint64_t b) {
  const uint64_t sum = uint64_t{a} + b;
  return static_cast<uint32_t>(std::min<uint64_t>(sum, std::numeric_limits<uint32_t>::max()));
}

// The .npy header: magic, version 1.0, header length, then a Python dict
// literal padded with spaces and a newline to a multiple of 64 bytes.
std::string NpyHeader(int height, int width) {
  std::string dict = absl::StrCat("{'descr': '<u4', 'fortran_order': False, 'shape': (", height, ", ",
                                  width, ", ", kNumRayKinds, ", ", kCostPerKind, "), }");
  const size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict.push_back('\n');
  std::string header("\x93NUMPY\x01\x00", 8);
  header.push_back(static_cast<char>(dict.size() & 0xff));
  header.push_back(static_cast<char>(dict.size() >> 8));
  return header + dict;
}

}  // namespace

void CostImage::Add(uint32_t pixel, RayKind kind, uint64_t inner_visits, uint64_t triangle_tests) {
  uint32_t* c = &counts[static_cast<size_t>(pixel) * kCostChannels + kCostPerKind * static_cast<int>(kind)];
  c[kCostRays] = SaturatingAdd(c[kCostRays], 1);
  c[kCostInnerVisits] = SaturatingAdd(c[kCostInnerVisits], inner_visits);
  c[kCostTriangleTests] = SaturatingAdd(c[kCostTriangleTests], triangle_tests);
}

absl::Status WriteCostImageNpyGz(const std::string& path, const CostImage& image) {
  if (image.width < 1 || image.height < 1 ||
      image.counts.size() != static_cast<size_t>(image.width) * image.height * kCostChannels) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": cost image buffer does not match ",
                                                   image.width, "x", image.height));
  }
  gzFile f = gzopen(path.c_str(), "wb6");
  if (f == nullptr) {
    return absl::InternalError(absl::StrCat(path, ": cannot open for writing: ", std::strerror(errno)));
  }
  const std::string header = NpyHeader(image.height, image.width);
  bool ok = gzwrite(f, header.data(), static_cast<unsigned>(header.size())) == static_cast<int>(header.size());
  // In chunks: gzwrite takes an unsigned length.
  const char* data = reinterpret_cast<const char*>(image.counts.data());
  const size_t bytes = image.counts.size() * sizeof(uint32_t);
  for (size_t off = 0; ok && off < bytes; off += (1u << 24)) {
    const unsigned n = static_cast<unsigned>(std::min<size_t>(bytes - off, 1u << 24));
    ok = gzwrite(f, data + off, n) == static_cast<int>(n);
  }
  if (gzclose(f) != Z_OK || !ok) {
    return absl::InternalError(absl::StrCat(path, ": cannot write the cost image"));
  }
  return absl::OkStatus();
}

}  // namespace kdtree
