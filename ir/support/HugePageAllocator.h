//===- HugePageAllocator.h - big tables on transparent huge pages -*- C++
//-*-===//
//
// A std::allocator replacement for the few tables that grow to hundreds of
// megabytes on large models (entity vectors, symbol tables, state stores).
// Blocks of 2 MiB and more are mapped directly and marked MADV_HUGEPAGE, so
// the kernel backs them with huge pages where it can: on a machine whose
// transparent huge pages are in `madvise` mode, this removes most of the
// page faults that otherwise dominate building a large net. Small blocks go
// to the ordinary allocator.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_HUGEPAGEALLOCATOR_H
#define NETLIFT_IR_SUPPORT_HUGEPAGEALLOCATOR_H

#include <cstddef>
#include <cstdint>
#include <new>
#include <sys/mman.h>

// LLVM's BumpPtrAllocator poisons its slabs under AddressSanitizer, and
// munmap does not clear the shadow: a later mapping at the same address
// would inherit that poison, so fresh mappings are unpoisoned explicitly.
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/asan_interface.h>
#define NETLIFT_UNPOISON(p, n) __asan_unpoison_memory_region(p, n)
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/asan_interface.h>
#define NETLIFT_UNPOISON(p, n) __asan_unpoison_memory_region(p, n)
#endif
#endif
#ifndef NETLIFT_UNPOISON
#define NETLIFT_UNPOISON(p, n) ((void)(p), (void)(n))
#endif

namespace netlift {

namespace detail {
constexpr size_t kHugeThreshold = size_t(2) << 20;
/// Mappings are rounded to whole, 2 MiB-aligned huge pages: mmap only
/// promises 4 KiB alignment, and the unaligned ends of a region are never
/// backed by huge pages (on a virtual machine with nested paging, the TLB
/// misses of 4 KiB pages cost more than the rest of a state-space search).
inline size_t hugeMappedBytes(size_t bytes) {
  return (bytes + kHugeThreshold - 1) & ~(kHugeThreshold - 1);
}
inline void *hugeAllocate(size_t bytes) {
  if (bytes < kHugeThreshold)
    return ::operator new(bytes);
  size_t size = hugeMappedBytes(bytes);
  // Over-map by one huge page, then unmap the unaligned head and the tail.
  void *raw = mmap(nullptr, size + kHugeThreshold, PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED)
    throw std::bad_alloc();
  uintptr_t begin = reinterpret_cast<uintptr_t>(raw);
  uintptr_t aligned = (begin + kHugeThreshold - 1) & ~(kHugeThreshold - 1);
  if (aligned > begin)
    munmap(raw, aligned - begin);
  if (uintptr_t end = begin + size + kHugeThreshold; end > aligned + size)
    munmap(reinterpret_cast<void *>(aligned + size), end - aligned - size);
  void *p = reinterpret_cast<void *>(aligned);
#ifdef MADV_HUGEPAGE
  madvise(p, size, MADV_HUGEPAGE);
#endif
  NETLIFT_UNPOISON(p, size);
  return p;
}
inline void hugeDeallocate(void *p, size_t bytes) {
  if (bytes < kHugeThreshold)
    ::operator delete(p);
  else
    munmap(p, hugeMappedBytes(bytes));
}
} // namespace detail

template <typename T> struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U> HugePageAllocator(const HugePageAllocator<U> &) {}
  T *allocate(size_t n) {
    return static_cast<T *>(detail::hugeAllocate(n * sizeof(T)));
  }
  void deallocate(T *p, size_t n) { detail::hugeDeallocate(p, n * sizeof(T)); }
  template <typename U> bool operator==(const HugePageAllocator<U> &) const {
    return true;
  }
  template <typename U> bool operator!=(const HugePageAllocator<U> &) const {
    return false;
  }
};

/// The same policy for llvm::BumpPtrAllocatorImpl's slabs.
struct HugePageSlabAllocator {
  void *Allocate(size_t size, size_t /*alignment*/) {
    return detail::hugeAllocate(size);
  }
  void Deallocate(const void *p, size_t size, size_t /*alignment*/) {
    detail::hugeDeallocate(const_cast<void *>(p), size);
  }
};

} // namespace netlift

#endif
