#pragma once
// Blocked ends of a replan through the fluid. The robot and the goal are particles in a moving
// fluid, so a frame often puts a neighbour within reach of one of them; rather than failing, an
// end that is not free moves to the nearest free spot within reach, and the plan runs from (to)
// there (plan/fluid_planner.hpp says which legs are then exempt from checking).
//  - on the occupancy grid: the centre of the nearest free cell (by distance from p to the
//    centre; ties: the lowest cell index) within `reach` cells (Chebyshev) of p's cell, p's
//    own cell first when it is free;
//  - in a continuous world: the first free point on rays from p in the 26 lattice directions,
//    stepping 0.05 out to `reach` (length); p itself when free.
//
// Threads: read-only on the world; reentrant.
#include <cmath>
#include <optional>

#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

std::optional<OccupancyWorld::Cell> escape_cell(const OccupancyWorld& world, const Vec<3>& p,
                                                int reach);

template <class W>
std::optional<Vec<3>> escape_point(const W& world, const Vec<3>& p, double reach) {
  if (world.point_free(p)) return p;
  constexpr double kStep = 0.05;
  for (double r = kStep; r <= reach + 1e-12; r += kStep)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          const double n = std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
          const Vec<3> q{p[0] + r * dx / n, p[1] + r * dy / n, p[2] + r * dz / n};
          if (world.point_free(q)) return q;
        }
  return std::nullopt;
}

}  // namespace hpcplan::env
