#include "cc/base/huge_pages.h"

#include <sys/mman.h>

#include <cstdlib>

namespace kdtree {

void* AllocateHugePages(size_t bytes) {
  const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) throw std::bad_alloc();
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) throw std::bad_alloc();
  // Before the first write: the kernel then backs each 2 MiB with one page.
  // A refusal (no THP support) leaves ordinary pages; nothing else changes.
  madvise(p, rounded, MADV_HUGEPAGE);
  return p;
}

void FreeHugePages(void* p) { std::free(p); }

}  // namespace kdtree
