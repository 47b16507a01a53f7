#pragma once
// A visited-map policy for graphs whose states are mostly small integers (the lattice
// vertices of a ContinuousGrid, the cells of the fluid's occupancy grid): keys below a bound set
// at run time are their own index into the stamped dense store (stamped_dense_map.hpp: arrays
// reused across runs, so a replanner allocates and clears nothing per plan), the rest (start,
// goal, sampled states) live in a hash map. Lattice neighbours are near each other in the
// array, so the search's map probes stop being cache misses. The store calls
// set_dense_keys(options.dense_keys) when the policy has it.
#include <algorithm>
#include <cstdint>
#include <utility>

#include <absl/container/flat_hash_map.h>

#include "hpcplan/search/stamped_dense_map.hpp"

namespace hpcplan::search {

template <class K, class V, class H>
class DenseThenHashMap {
  using Dense = StampedDenseMap<K, V, H>;

 public:
  using Slot = typename Dense::Slot;
  using iterator = Slot*;

  void set_dense_keys(std::uint64_t n) {
    dense_n_ = n;
    if (n != 0) dense_.set_dense_keys(n);
  }
  void reserve(std::size_t n) { sparse_.reserve(std::min<std::size_t>(n, 1024)); }

  std::pair<Slot*, bool> try_emplace(const K& k, const V& v) {
    if (static_cast<std::uint64_t>(k) < dense_n_) return dense_.try_emplace_at(k, v);
    auto [it, inserted] = sparse_.try_emplace(k, Slot{v});
    return {&it->second, inserted};
  }
  Slot* find(const K& k) {
    if (static_cast<std::uint64_t>(k) < dense_n_) return dense_.find_at(k);
    auto it = sparse_.find(k);
    return it == sparse_.end() ? nullptr : &it->second;
  }
  const Slot* find(const K& k) const { return const_cast<DenseThenHashMap*>(this)->find(k); }
  Slot* end() const { return nullptr; }
  std::size_t size() const { return dense_.size() + sparse_.size(); }

 private:
  Dense dense_;
  std::uint64_t dense_n_ = 0;
  absl::flat_hash_map<K, Slot, H> sparse_;
};

struct DenseThenHashPolicy {
  static constexpr const char* name =
      "dense array (generation-stamped, reused) + absl::flat_hash_map";
  template <class K, class V, class H>
  using type = DenseThenHashMap<K, V, H>;
};

}  // namespace hpcplan::search
