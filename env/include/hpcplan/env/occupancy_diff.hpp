#pragma once
// What changed between two frames' occupancy grids of the same box, as an incremental search
// (D* Lite) needs it: a cell whose occupancy flipped changes the edges of every cell in its
// 26-neighbourhood, so those are the cells whose out-edges must be re-examined.
//
// Threads: read-only on both grids; reentrant.
#include <cstdint>
#include <vector>

#include "hpcplan/env/occupancy_world.hpp"

namespace hpcplan::env {

struct OccupancyDiff {
  std::uint64_t changed = 0;           // cells whose occupancy differs
  std::vector<std::uint32_t> touched;  // those and their neighbours: sorted, unique indices
};

// `before` and `after` must have the same cells per axis (InputError otherwise).
OccupancyDiff occupancy_diff(const OccupancyWorld& before, const OccupancyWorld& after);

}  // namespace hpcplan::env
