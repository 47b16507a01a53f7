#pragma once
// A collision-check counter that an immutable world may bump from const queries while several
// planner threads read the world at once. Relaxed atomic increments: each count is exact, and
// no ordering with anything else is implied. Copying a world copies the count so far.
//
// A run's own count is the change of this_thread() over the run (a run plans on one thread):
// the world's total also counts the other threads that share it.
#include <atomic>
#include <cstdint>

namespace hpcplan {

class CheckCounter {
 public:
  CheckCounter() = default;
  CheckCounter(const CheckCounter& other) : n_(other.value()) {}
  CheckCounter& operator=(const CheckCounter& other) {
    n_.store(other.value(), std::memory_order_relaxed);
    return *this;
  }

  void add(std::uint64_t k = 1) const {
    n_.fetch_add(k, std::memory_order_relaxed);
    thread_count() += k;
  }
  std::uint64_t value() const { return n_.load(std::memory_order_relaxed); }

  // Checks the calling thread has made on every world so far.
  static std::uint64_t this_thread() { return thread_count(); }

 private:
  static std::uint64_t& thread_count() {
    thread_local std::uint64_t n = 0;
    return n;
  }
  mutable std::atomic<std::uint64_t> n_{0};
};

}  // namespace hpcplan
