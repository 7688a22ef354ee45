// FNV-1a hashes, 64-bit (G. Fowler, L. C. Noll, K.-P. Vo; the offset basis and
// prime of the FNV reference), the one implementation behind every checksum
// and fingerprint of the project: byte by byte (the image hash of kdrt's
// record, the soup cache's key), or one multiply per little-endian 64-bit
// word (the soup cache's and the ray dump's checksums, the tree
// fingerprint), which hashes hundreds of megabytes in a fraction of the time.
// A word-wise hash needs a rule for a tail shorter than 8 bytes; the two
// formats that store one differ, so it is a parameter. (The tree fingerprint
// also starts from its own, historical offset basis: cc/kdtree/stats.cc.)
#ifndef KDTREE_CC_BASE_FNV_H_
#define KDTREE_CC_BASE_FNV_H_

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace kdtree {

inline constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull;
inline constexpr uint64_t kFnvPrime = 0x100000001b3ull;

// h = (h ^ byte) * prime for every byte.
inline uint64_t FnvBytes(const void* data, size_t size, uint64_t h = kFnvOffset) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) h = (h ^ p[i]) * kFnvPrime;
  return h;
}

// How FnvWords hashes the last size % 8 bytes: as one word zero-padded at the
// top (the soup cache, cc/io/soup_cache.h), or byte by byte (the tree
// fingerprint, cc/kdtree/stats.h).
enum class FnvTail { kZeroPaddedWord, kBytes };

// h = (h ^ w) * prime for every little-endian 64-bit word w, then the tail.
inline uint64_t FnvWords(const void* data, size_t size, uint64_t h = kFnvOffset,
                         FnvTail tail = FnvTail::kZeroPaddedWord) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "words are read little-endian");
  const unsigned char* p = static_cast<const unsigned char*>(data);
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = (h ^ w) * kFnvPrime;
  }
  if (i == size) return h;
  if (tail == FnvTail::kBytes) return FnvBytes(p + i, size - i, h);
  uint64_t w = 0;
  std::memcpy(&w, p + i, size - i);
  return (h ^ w) * kFnvPrime;
}

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_FNV_H_
