#pragma once
// Objects of one type kept idle between uses, process-wide, with whatever they already hold
// (vector capacity, mapped pages). Searches borrow their big buffers here: a buffer freed at
// the end of a run is handed back to the kernel by glibc and has to be faulted in again by the
// next run. Process-wide rather than thread-local, because OMPL's benchmark runs every solve
// on a fresh thread.
//
// Threads: take() and keep() may be called from any thread (one mutex per type); an object
// taken belongs to its taker until kept again.
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace hpcplan {

template <class T>
class IdlePool {
 public:
  // An idle object, or null when none waits.
  static std::unique_ptr<T> take() {
    State& s = state();
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (s.idle.empty()) return nullptr;
    std::unique_ptr<T> t = std::move(s.idle.back());
    s.idle.pop_back();
    return t;
  }
  static void keep(std::unique_ptr<T> t) {
    if (!t) return;
    State& s = state();
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.idle.push_back(std::move(t));
  }

 private:
  struct State {
    std::mutex mutex;
    std::vector<std::unique_ptr<T>> idle;
  };
  static State& state() {
    static State s;
    return s;
  }
};

}  // namespace hpcplan
