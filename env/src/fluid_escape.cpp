#include "hpcplan/env/fluid_escape.hpp"

namespace hpcplan::env {

std::optional<OccupancyWorld::Cell> escape_cell(const OccupancyWorld& w, const Vec<3>& p,
                                                int reach) {
  using Cell = OccupancyWorld::Cell;
  const Cell c = w.cell_of(p);
  if (!w.occupied(c)) return c;
  std::optional<Cell> best;
  double best_d2 = 0.0;
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const Cell q{c[0] + dx, c[1] + dy, c[2] + dz};
        if (!w.inside(q) || w.occupied(q)) continue;
        const Vec<3> m = w.centre(q);
        const double d2 = (m[0] - p[0]) * (m[0] - p[0]) + (m[1] - p[1]) * (m[1] - p[1]) +
                          (m[2] - p[2]) * (m[2] - p[2]);
        if (!best || d2 < best_d2 || (d2 == best_d2 && w.index(q) < w.index(*best)))
          best = q, best_d2 = d2;
      }
  w.count_checks(static_cast<std::uint64_t>((2 * reach + 1) * (2 * reach + 1) * (2 * reach + 1)));
  return best;
}

}  // namespace hpcplan::env
