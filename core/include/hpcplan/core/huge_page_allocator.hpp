#pragma once
// An allocator for the search's big tables (visited map, open-list heap) that asks the kernel
// for transparent huge pages. Searches touch these tables at random, so with 4 KiB pages
// they pay a TLB miss on most probes and one page fault per 4 KiB as a table grows: on the
// VMs we measure on a fault costs ~20 us, and the faults of one rehash stall a rank for
// ~100 ms while its peers wait at the next exchange. With THP in "madvise" mode (the Debian
// default) a 2 MiB-aligned region marked MADV_HUGEPAGE is faulted in 2 MiB at a time.
// Blocks under 2 MiB come from the ordinary heap, and so does everything in sanitizer builds,
// which can only check memory that comes through malloc.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>

namespace hpcplan {

namespace huge_pages {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kEnabled = false;
#else
inline constexpr bool kEnabled = true;
#endif

inline std::size_t rounded(std::size_t bytes) {
  return (bytes + kHugePage - 1) & ~(kHugePage - 1);
}

// A 2 MiB-aligned anonymous mapping of at least `bytes`, marked for huge pages.
inline void* map(std::size_t bytes) {
  const std::size_t size = rounded(bytes);
  // Over-map by one huge page and trim both ends to get the alignment.
  const std::size_t span = size + kHugePage;
  void* raw = ::mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto base = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (base + kHugePage - 1) & ~(kHugePage - 1);
  if (aligned > base) ::munmap(raw, aligned - base);
  const std::uintptr_t end = base + span;
  if (end > aligned + size) ::munmap(reinterpret_cast<void*>(aligned + size), end - aligned - size);
  void* p = reinterpret_cast<void*>(aligned);
  // Advice only: where THP is off the mapping still works with small pages.
  ::madvise(p, size, MADV_HUGEPAGE);
  return p;
}

inline void unmap(void* p, std::size_t bytes) {
  ::munmap(p, rounded(bytes));
}

}  // namespace huge_pages

template <class T>
class HugePageAllocator {
 public:
  using value_type = T;

  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
    if (!huge_pages::kEnabled || bytes < huge_pages::kHugePage)
      return std::allocator<T>().allocate(n);
    return static_cast<T*>(huge_pages::map(bytes));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (!huge_pages::kEnabled || bytes < huge_pages::kHugePage)
      std::allocator<T>().deallocate(p, n);
    else
      huge_pages::unmap(p, bytes);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace hpcplan
