#pragma once
// The CPUs this process may run on: its affinity mask, which is what taskset, a SLURM job's
// cgroup (--cpus-per-task) or mpirun's binding (--bind-to core, --map-by ...:PE=n) left it,
// rather than every core of the machine (std::thread::hardware_concurrency). A process's
// default thread count is its share of these.
//
// Threads: reads the calling thread's mask; call it before starting threads of its own.
#include <array>
#include <cstdint>

namespace hpcplan {

class CpuSet {
 public:
  static constexpr int kWords = 16;  // 1024 CPUs, glibc's CPU_SETSIZE

  // This process's set (every CPU the machine has online if the mask cannot be read).
  static CpuSet of_this_process();

  int count() const;  // at least 1
  bool overlaps(const CpuSet& other) const;
  const std::array<std::uint64_t, kWords>& words() const { return words_; }
  static CpuSet from_words(const std::array<std::uint64_t, kWords>& w) {
    CpuSet s;
    s.words_ = w;
    return s;
  }

 private:
  std::array<std::uint64_t, kWords> words_{};
};

}  // namespace hpcplan
