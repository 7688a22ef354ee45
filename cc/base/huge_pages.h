// Large arrays on transparent huge pages (2 MiB) instead of 4 KiB pages.
//
// A kd-tree build touches hundreds of megabytes of fresh memory (build
// references, nodes, leaf lists, leaf packets), and traversal walks it in an
// order no TLB of 4 KiB pages covers. On the measured machines transparent
// huge pages are granted only on request (/sys/kernel/mm/transparent_hugepage/
// enabled = madvise), so an array that never asks pays one page fault per
// 4 KiB when it is first written and a TLB miss on most node visits. Embree
// asks for huge pages by default on Linux (rtcNewDevice(3), "hugepages"); this
// allocator asks too, so that the two tracers are compared on equal terms.
//
// HugePageAllocator<T> serves requests of at least kHugePageBytes from
// 2 MiB-aligned memory advised with madvise(MADV_HUGEPAGE) (a hint: the kernel
// may refuse, and the memory is then ordinary); smaller requests go to
// operator new. HugeVector<T> is a std::vector using it.
//
// Reuse. The first write to fresh memory costs the kernel a page fault and the
// zeroing of the page; on the measured virtual machines that runs at 0.5 to
// 1.5 GB/s, 10 to 30 times slower than writing memory already backed, so a
// build that writes 400 MB of leaf packets spent a third of its time in the
// kernel's clear_page (perf). Freed blocks are therefore kept, as a renderer
// that rebuilds its tree keeps its memory, and handed to the next request
// they fit (best fit, at most twice the size asked for). The limit counts the
// memory the kept blocks hold (mincore when a block is freed; a block never
// written is not kept), half of physical memory by default
// (SetHugePageCacheLimit). It cannot count address space: the builder
// reserves 8 times what it writes (builder.cc), and a parallel build's 30
// fragments reserve 12 GB on asian-dragon, which a limit on address space
// turned away so that every parallel build took fresh pages. A build in a
// fresh process still pays for fresh pages: benchmarks record every repeat,
// the first one included (build_bench, kdrt's T_B_runs).
#ifndef KDTREE_CC_BASE_HUGE_PAGES_H_
#define KDTREE_CC_BASE_HUGE_PAGES_H_

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace kdtree {

inline constexpr size_t kHugePageBytes = size_t{2} << 20;

// Memory for `bytes` (>= kHugePageBytes): 2 MiB-aligned, rounded up to whole
// huge pages, advised MADV_HUGEPAGE. Throws std::bad_alloc when out of memory.
// The memory is not zeroed: it may be a block freed before (see Reuse).
void* AllocateHugePages(size_t bytes);
// `bytes` as given to AllocateHugePages.
void FreeHugePages(void* p, size_t bytes);

// The reuse cache: freed blocks holding at most `bytes` of memory are kept
// (0 = none, every block is freed at once); lowering the limit frees blocks
// to meet it. HugePageCacheBytes() is the memory the kept blocks hold.
inline constexpr size_t kMaxCachedBlocks = 256;
size_t DefaultHugePageCacheLimit();  // half of physical memory
void SetHugePageCacheLimit(size_t bytes);
size_t HugePageCacheBytes();

template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}  // NOLINT: rebinding

  T* allocate(size_t n) {
    if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(AllocateHugePages(bytes));
  }
  void deallocate(T* p, size_t n) {
    // The same size decides the same way as in allocate.
    if (n * sizeof(T) < kHugePageBytes) {
      ::operator delete(p);
    } else {
      FreeHugePages(p, n * sizeof(T));
    }
  }
};

template <class T, class U>
bool operator==(const HugePageAllocator<T>&, const HugePageAllocator<U>&) {
  return true;
}
template <class T, class U>
bool operator!=(const HugePageAllocator<T>&, const HugePageAllocator<U>&) {
  return false;
}

template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

// HugePageAllocator whose value-initialisation is default-initialisation:
// resize() of a HugeBuffer leaves new trivial elements unwritten instead of
// zeroing them, for arrays that are filled right after (a pass fewer over
// hundreds of megabytes, and a fill that can run in parallel).
template <class T>
struct HugePageNoInitAllocator : HugePageAllocator<T> {
  template <class U>
  struct rebind {
    using other = HugePageNoInitAllocator<U>;
  };
  HugePageNoInitAllocator() = default;
  template <class U>
  HugePageNoInitAllocator(const HugePageNoInitAllocator<U>&) {}  // NOLINT: rebinding

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using HugeBuffer = std::vector<T, HugePageNoInitAllocator<T>>;

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_HUGE_PAGES_H_
