#pragma once
// A visited-map policy for graphs whose states are mostly small integers (the lattice
// vertices of a ContinuousGrid): keys below a bound set at run time live in a flat array
// indexed by the key, the rest (start, goal, sampled states) in a hash map. Lattice
// neighbours are near each other in the array, so the search's map probes stop being cache
// misses; the array comes from the huge-page allocator, so pages the search never touches are
// never faulted in. The store calls set_dense_keys(options.dense_keys) when the policy has it.
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>

#include <absl/container/flat_hash_map.h>

#include "hpcplan/core/huge_page_allocator.hpp"

namespace hpcplan::search {

template <class K, class V, class H>
class DenseThenHashMap {
 public:
  struct Slot {
    V second;  // named like a map entry's value, so the store reads it the same way
  };
  using iterator = Slot*;

  DenseThenHashMap() = default;
  DenseThenHashMap(const DenseThenHashMap&) = delete;
  DenseThenHashMap& operator=(const DenseThenHashMap&) = delete;
  ~DenseThenHashMap() { release(); }

  void set_dense_keys(std::uint64_t n) {
    release();
    if (n == 0) return;
    slots_ = HugePageAllocator<Slot>().allocate(n);
    present_ = HugePageAllocator<std::uint8_t>().allocate(n);
    std::memset(present_, 0, n);
    dense_n_ = n;
  }
  void reserve(std::size_t n) { sparse_.reserve(std::min<std::size_t>(n, 1024)); }

  std::pair<Slot*, bool> try_emplace(const K& k, const V& v) {
    if (static_cast<std::uint64_t>(k) < dense_n_) {
      if (present_[k]) return {&slots_[k], false};
      present_[k] = 1;
      ++dense_count_;
      std::construct_at(&slots_[k], Slot{v});
      return {&slots_[k], true};
    }
    auto [it, inserted] = sparse_.try_emplace(k, Slot{v});
    return {&it->second, inserted};
  }
  Slot* find(const K& k) {
    if (static_cast<std::uint64_t>(k) < dense_n_) return present_[k] ? &slots_[k] : nullptr;
    auto it = sparse_.find(k);
    return it == sparse_.end() ? nullptr : &it->second;
  }
  const Slot* find(const K& k) const { return const_cast<DenseThenHashMap*>(this)->find(k); }
  Slot* end() const { return nullptr; }
  std::size_t size() const { return dense_count_ + sparse_.size(); }

 private:
  void release() {
    if (dense_n_ == 0) return;
    HugePageAllocator<Slot>().deallocate(slots_, dense_n_);
    HugePageAllocator<std::uint8_t>().deallocate(present_, dense_n_);
    dense_n_ = dense_count_ = 0;
  }

  Slot* slots_ = nullptr;
  std::uint8_t* present_ = nullptr;
  std::uint64_t dense_n_ = 0;
  std::size_t dense_count_ = 0;
  absl::flat_hash_map<K, Slot, H> sparse_;
};

struct DenseThenHashPolicy {
  static constexpr const char* name = "dense array + absl::flat_hash_map";
  template <class K, class V, class H>
  using type = DenseThenHashMap<K, V, H>;
};

}  // namespace hpcplan::search
