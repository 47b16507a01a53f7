#include "hpcplan/core/cpu_set.hpp"

#include <sched.h>
#include <unistd.h>

#include <bit>
#include <thread>

namespace hpcplan {

CpuSet CpuSet::of_this_process() {
  CpuSet s;
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) == 0) {
    for (int c = 0; c < kWords * 64 && c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &mask)) s.words_[c / 64] |= std::uint64_t{1} << (c % 64);
  } else {
    const int n = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    for (int c = 0; c < n && c < kWords * 64; ++c) s.words_[c / 64] |= std::uint64_t{1} << (c % 64);
  }
  return s;
}

int CpuSet::count() const {
  int n = 0;
  for (std::uint64_t w : words_) n += std::popcount(w);
  return n > 0 ? n : 1;
}

bool CpuSet::overlaps(const CpuSet& other) const {
  for (int i = 0; i < kWords; ++i)
    if (words_[i] & other.words_[i]) return true;
  return false;
}

}  // namespace hpcplan
