// The builder's pool of build references: a growable array of BuildRef (or of
// bare triangle indices, IndexRef, for builds whose boxes never change) that
// hands out raw pointers, so that a partition writes its children's
// references with plain stores (no per-element capacity check, no
// construction of elements that are about to be overwritten).
//
// std::vector cannot append without constructing (resize() runs AABB's
// default constructor on every new element; push_back() checks capacity per
// element). RefPool keeps size and capacity itself: Reserve() grows the
// storage (memcpy: Ref is trivially copyable), Reserved() returns the
// first of `n` slots past the end for the caller to fill, Resize() shrinks or
// commits slots already written, Append() copies references in. Storage comes from HugePageAllocator (huge
// pages when large, as the rest of the tree's arrays).
#ifndef KDTREE_CC_KDTREE_REF_POOL_H_
#define KDTREE_CC_KDTREE_REF_POOL_H_

#include <cassert>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "cc/base/huge_pages.h"
#include "cc/kdtree/build_ref.h"

namespace kdtree {

template <class Ref>
class RefPoolOf {
  static_assert(std::is_trivially_copyable<Ref>::value, "RefPool copies with memcpy");

 public:
  RefPoolOf() = default;
  RefPoolOf(const RefPoolOf&) = delete;
  RefPoolOf& operator=(const RefPoolOf&) = delete;
  ~RefPoolOf() { Free(); }

  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  Ref* data() { return data_; }
  const Ref* data() const { return data_; }
  Ref& operator[](size_t i) {
    assert(i < size_);
    return data_[i];
  }

  // Capacity for at least `n` references; pointers into the pool are
  // invalidated when it grows.
  void Reserve(size_t n) {
    if (n <= capacity_) return;
    const size_t grown = capacity_ + capacity_ / 2;
    const size_t cap = n > grown ? n : grown;
    Ref* fresh = HugePageAllocator<Ref>().allocate(cap);
    const size_t size = size_;
    if (size > 0) std::memcpy(fresh, data_, size * sizeof(Ref));
    Free();
    data_ = fresh;
    capacity_ = cap;
    size_ = size;
  }

  // Slots size() .. size() + n - 1 exist after this (contents undefined until
  // written); size() is unchanged. Returns a pointer to the first.
  Ref* Reserved(size_t n) {
    Reserve(size_ + n);
    return data_ + size_;
  }

  // New size: smaller drops the tail; larger commits slots written through
  // Reserved() (n <= capacity()).
  void Resize(size_t n) {
    assert(n <= capacity_);
    size_ = n;
  }

  // Appends refs[0 .. n-1] (which must not point into this pool).
  void Append(const Ref* refs, size_t n) {
    Reserve(size_ + n);
    if (n > 0) std::memcpy(data_ + size_, refs, n * sizeof(Ref));
    size_ += n;
  }

 private:
  void Free() {
    if (data_ != nullptr) HugePageAllocator<Ref>().deallocate(data_, capacity_);
    data_ = nullptr;
    capacity_ = size_ = 0;
  }

  Ref* data_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

using RefPool = RefPoolOf<BuildRef>;

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_REF_POOL_H_
