#pragma once
// A collision-check counter that an immutable world may bump from const queries while several
// planner threads read the world at once.
//
// A run's own count is the change of this_thread() over the run (a run plans on one thread):
// a thread-local count, exact whatever the other threads do. The world's total is a relaxed
// atomic bumped by a plain load and store rather than a locked add (a locked add on every
// segment test cost 10-20% of a tightening-heavy plan): exact while one thread uses the world,
// and free of data races but possibly short by the overlapping increments when several do.
// Copying a world copies the count so far.
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
    n_.store(n_.load(std::memory_order_relaxed) + k, std::memory_order_relaxed);
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
