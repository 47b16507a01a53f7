#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include <absl/container/flat_hash_map.h>

#include "hpcplan/core/huge_page_allocator.hpp"

namespace hpcplan {
namespace {

TEST(HugePageAllocator, LargeBlocksAreHugePageAlignedAndUsable) {
  HugePageAllocator<std::uint64_t> a;
  const std::size_t n = (std::size_t{5} << 20) / sizeof(std::uint64_t);  // 5 MiB: not a multiple
  std::uint64_t* p = a.allocate(n);
  ASSERT_NE(p, nullptr);
  if (huge_pages::kEnabled) {
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % huge_pages::kHugePage, 0u);
  }
  for (std::size_t i = 0; i < n; ++i) p[i] = i * 3;  // every byte of the block is writable
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += p[i];
  EXPECT_EQ(sum, 3 * (n * (n - 1) / 2));
  a.deallocate(p, n);
}

TEST(HugePageAllocator, SmallBlocksComeFromTheHeap) {
  HugePageAllocator<int> a;
  int* p = a.allocate(10);
  std::iota(p, p + 10, 0);
  EXPECT_EQ(p[9], 9);
  a.deallocate(p, 10);
}

TEST(HugePageAllocator, ImpossibleSizeThrowsBadAlloc) {
  HugePageAllocator<std::uint64_t> a;
  EXPECT_THROW((void)a.allocate(std::numeric_limits<std::size_t>::max() / 4), std::bad_alloc);
}

TEST(HugePageAllocator, ContainersGrowThroughTheThreshold) {
  std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> v;
  for (std::uint32_t i = 0; i < 3'000'000; ++i) v.push_back(i);  // reallocates past 2 MiB
  EXPECT_EQ(v[2'999'999], 2'999'999u);
  absl::flat_hash_map<std::uint64_t, std::uint64_t, absl::Hash<std::uint64_t>,
                      std::equal_to<std::uint64_t>,
                      HugePageAllocator<std::pair<const std::uint64_t, std::uint64_t>>>
      m;
  for (std::uint64_t i = 0; i < 400'000; ++i) m[i * 7919] = i;
  for (std::uint64_t i = 0; i < 400'000; i += 997) EXPECT_EQ(m.at(i * 7919), i);
}

}  // namespace
}  // namespace hpcplan
