#include "cc/base/huge_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <vector>

namespace kdtree {
namespace {

struct Block {
  void* p;
  size_t bytes;     // rounded to whole huge pages
  size_t resident;  // bytes backed by memory when it was freed (mincore)
};

// Freed blocks kept for reuse (see "Reuse" in huge_pages.h).
struct Cache {
  std::mutex mu;
  std::vector<Block> blocks;
  size_t bytes = 0;  // resident bytes of `blocks`
  size_t limit = DefaultHugePageCacheLimit();
};

Cache& TheCache() {
  static Cache* cache = new Cache();  // never destroyed: used until exit
  return *cache;
}

// Bytes of [p, p + bytes) backed by memory (0 when mincore fails).
size_t ResidentBytes(void* p, size_t bytes) {
  const long page = sysconf(_SC_PAGESIZE);
  if (page <= 0) return 0;
  const size_t pages = (bytes + static_cast<size_t>(page) - 1) / static_cast<size_t>(page);
  std::vector<unsigned char> in_core(pages);
  if (mincore(p, bytes, in_core.data()) != 0) return 0;
  size_t resident = 0;
  for (unsigned char c : in_core) resident += c & 1;
  return resident * static_cast<size_t>(page);
}

size_t Rounded(size_t bytes) {
  const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) throw std::bad_alloc();
  return rounded;
}

}  // namespace

size_t DefaultHugePageCacheLimit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<size_t>(pages) * static_cast<size_t>(page) / 2;
}

namespace {
// Frees kept blocks until they hold at most `keep` bytes.
void Trim(size_t keep) {
  Cache& c = TheCache();
  std::vector<Block> drop;
  {
    std::lock_guard<std::mutex> lock(c.mu);
    while (c.bytes > keep && !c.blocks.empty()) {
      drop.push_back(c.blocks.back());
      c.bytes -= c.blocks.back().resident;
      c.blocks.pop_back();
    }
  }
  for (const Block& b : drop) std::free(b.p);
}
}  // namespace

void SetHugePageCacheLimit(size_t bytes) {
  {
    Cache& c = TheCache();
    std::lock_guard<std::mutex> lock(c.mu);
    c.limit = bytes;
  }
  Trim(bytes);
}

size_t HugePageCacheBytes() {
  Cache& c = TheCache();
  std::lock_guard<std::mutex> lock(c.mu);
  return c.bytes;
}

void* AllocateHugePages(size_t bytes) {
  const size_t rounded = Rounded(bytes);
  {
    // Best fit among the kept blocks: the smallest that is large enough and
    // at most twice the request (a small array must not take the block a
    // large one will ask for next: that one would get fresh pages).
    Cache& c = TheCache();
    std::lock_guard<std::mutex> lock(c.mu);
    size_t best = c.blocks.size();
    for (size_t i = 0; i < c.blocks.size(); ++i) {
      if (c.blocks[i].bytes >= rounded && c.blocks[i].bytes / 2 <= rounded &&
          (best == c.blocks.size() || c.blocks[i].bytes < c.blocks[best].bytes)) {
        best = i;
      }
    }
    if (best != c.blocks.size()) {
      void* p = c.blocks[best].p;
      c.bytes -= c.blocks[best].resident;
      c.blocks[best] = c.blocks.back();
      c.blocks.pop_back();
      return p;
    }
  }
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) {
    // Memory the cache holds may be what is missing: give it back and retry.
    Trim(0);
    p = std::aligned_alloc(kHugePageBytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
  }
  // Before the first write: the kernel then backs each 2 MiB with one page.
  // A refusal (no THP support) leaves ordinary pages; nothing else changes.
  madvise(p, rounded, MADV_HUGEPAGE);
  return p;
}

void FreeHugePages(void* p, size_t bytes) {
  if (p == nullptr) return;
  const size_t rounded = Rounded(bytes);
  // Only memory already backed saves anything; the limit counts that.
  const size_t resident = ResidentBytes(p, rounded);
  if (resident > 0) {
    Cache& c = TheCache();
    std::lock_guard<std::mutex> lock(c.mu);
    if (c.bytes + resident <= c.limit && c.blocks.size() < kMaxCachedBlocks) {
      c.blocks.push_back(Block{p, rounded, resident});
      c.bytes += resident;
      return;
    }
  }
  std::free(p);
}

}  // namespace kdtree
