#pragma once
// Visited-map policies: the engine is parameterised by the hash map that stores g-values and
// parent moves, so alternatives can be measured (bench/) without touching the algorithm.
#include <unordered_map>

#include <absl/container/flat_hash_map.h>

#include "hpcplan/core/huge_page_allocator.hpp"

namespace hpcplan::search {

// Tables of 2 MiB and more live on transparent huge pages (core/huge_page_allocator.hpp).
struct AbslFlatMap {
  static constexpr const char* name = "absl::flat_hash_map";
  template <class K, class V, class H>
  using type =
      absl::flat_hash_map<K, V, H, std::equal_to<K>, HugePageAllocator<std::pair<const K, V>>>;
};

struct StdUnorderedMap {
  static constexpr const char* name = "std::unordered_map";
  template <class K, class V, class H>
  using type = std::unordered_map<K, V, H>;
};

using DefaultVisitedMap = AbslFlatMap;

}  // namespace hpcplan::search
