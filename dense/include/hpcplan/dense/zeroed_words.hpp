#pragma once
// A zero-filled array of words that costs memory only where it is written: an anonymous
// mapping on huge pages (the kernel hands out zero pages on first touch), so a BFS that stops
// early never faults in the lattice's far side, and a slab's array costs nothing before the
// wavefront reaches it. Sanitizer builds take calloc instead, which the sanitizers can check.
//
// Threads: an array belongs to its engine; threads write disjoint words of it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "hpcplan/core/huge_page_allocator.hpp"

namespace hpcplan::dense {

class ZeroedWords {
 public:
  ZeroedWords() = default;
  explicit ZeroedWords(std::size_t words) : size_(words) {
    if (words == 0) return;
    const std::size_t bytes = words * sizeof(std::uint64_t);
    if constexpr (huge_pages::kEnabled) {
      data_ = static_cast<std::uint64_t*>(huge_pages::map(bytes));
    } else {
      data_ = static_cast<std::uint64_t*>(std::calloc(words, sizeof(std::uint64_t)));
      if (!data_) throw std::bad_alloc();
    }
  }
  ~ZeroedWords() { release(); }
  ZeroedWords(const ZeroedWords&) = delete;
  ZeroedWords& operator=(const ZeroedWords&) = delete;
  ZeroedWords(ZeroedWords&& o) noexcept : data_(o.data_), size_(o.size_) {
    o.data_ = nullptr;
    o.size_ = 0;
  }
  ZeroedWords& operator=(ZeroedWords&& o) noexcept {
    if (this != &o) {
      release();
      data_ = o.data_;
      size_ = o.size_;
      o.data_ = nullptr;
      o.size_ = 0;
    }
    return *this;
  }

  std::uint64_t* data() { return data_; }
  const std::uint64_t* data() const { return data_; }
  std::uint64_t& operator[](std::size_t i) { return data_[i]; }
  std::uint64_t operator[](std::size_t i) const { return data_[i]; }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return size_ * sizeof(std::uint64_t); }

 private:
  void release() {
    if (!data_) return;
    if constexpr (huge_pages::kEnabled)
      huge_pages::unmap(data_, size_ * sizeof(std::uint64_t));
    else
      std::free(data_);
    data_ = nullptr;
  }
  std::uint64_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace hpcplan::dense
