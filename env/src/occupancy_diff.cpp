#include "hpcplan/env/occupancy_diff.hpp"

#include <algorithm>

#include "hpcplan/core/error.hpp"

namespace hpcplan::env {

OccupancyDiff occupancy_diff(const OccupancyWorld& before, const OccupancyWorld& after) {
  if (before.cells_per_axis() != after.cells_per_axis())
    throw InputError("occupancy_diff: the two grids have different cells per axis");
  OccupancyDiff d;
  for (std::uint32_t i = 0; i < after.cell_count(); ++i) {
    if (after.occupied(i) == before.occupied(i)) continue;
    ++d.changed;
    const OccupancyWorld::Cell c = after.cell_of_index(i);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const OccupancyWorld::Cell q{c[0] + dx, c[1] + dy, c[2] + dz};
          if (after.inside(q)) d.touched.push_back(after.index(q));
        }
  }
  std::sort(d.touched.begin(), d.touched.end());
  d.touched.erase(std::unique(d.touched.begin(), d.touched.end()), d.touched.end());
  return d;
}

}  // namespace hpcplan::env
