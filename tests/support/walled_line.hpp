#pragma once
// A 1D GOG problem whose start and goal are free but separated by a blocked cell: no path can
// cross it, so every planner must answer no_path. Shared by the serial and MPI suites.
#include <cstdint>
#include <vector>

#include "hpcplan/plan/grid_problem.hpp"

namespace hpcplan::test_support {

inline GridProblem walled_line() {
  for (std::uint64_t seed = 1;; ++seed) {
    GridProblem p;
    p.dims = 1;
    p.extent = 64;
    p.gog.seed = seed;
    p.gog.shift_v = 2;
    p.gog.threshold = 2;
    const GogField f(1, 64, p.gog);
    if (!f.is_free(std::vector<int>{0}) || !f.is_free(std::vector<int>{63})) continue;
    for (int c = 1; c + 1 < 64; ++c)
      if (!f.is_free(std::vector<int>{c})) {
        p.start = std::vector<int>{0};
        p.goal = std::vector<int>{63};
        return p;
      }
  }
}

}  // namespace hpcplan::test_support
