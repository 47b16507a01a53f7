#pragma once
// A further visited-map policy for comparison benchmarks (kept out of the library).
#include <tsl/robin_map.h>

namespace hpcplan::bench {

struct TslRobinMap {
  static constexpr const char* name = "tsl::robin_map";
  template <class K, class V, class H>
  using type = tsl::robin_map<K, V, H>;
};

}  // namespace hpcplan::bench
