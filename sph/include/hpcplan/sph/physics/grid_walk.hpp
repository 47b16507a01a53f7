#pragma once
// The neighbour grid's geometry and its walk, on the host and the GPU (see physics.hpp).
// Cells no smaller than the support cover the particles' region, numbered x fastest, so the 3
// cells of one x-row around a point are consecutive: a query walks 9 rows, not 27 cells. The
// backends differ only in how a row's particles are listed (CSR buckets on the CPU, ranges of
// the cell-sorted arrays on the GPU), which they pass in as `row_items`.
#include <cstdint>

#include "hpcplan/core/portable.hpp"

namespace hpcplan::sph {

struct GridGeometry {
  double lo[3] = {0, 0, 0};        // the region's low corner
  double inv_cell[3] = {0, 0, 0};  // cells per unit length, per axis
  std::int64_t n[3] = {1, 1, 1};   // cells per axis
};

// The cell coordinate of v on axis k, clamped to the grid (a particle outside the region is
// filed in the nearest border cell: still found, only slower). NaN maps to cell 0.
HPCPLAN_HD inline std::int64_t cell_coordinate(const GridGeometry& g, double v, int k) {
  const double c = (v - g.lo[k]) * g.inv_cell[k];
  if (!(c >= 0.0)) return 0;
  if (c >= static_cast<double>(g.n[k])) return g.n[k] - 1;
  return static_cast<std::int64_t>(c);
}

HPCPLAN_HD inline std::uint32_t cell_key(const GridGeometry& g, double x, double y, double z) {
  return static_cast<std::uint32_t>(
      cell_coordinate(g, x, 0) +
      g.n[0] * (cell_coordinate(g, y, 1) + g.n[1] * cell_coordinate(g, z, 2)));
}

// row(first, last) for each of the (up to 9) x-rows of cells first .. last (1 to 3 cells)
// around the cell of (x, y, z): rows by z, then y.
template <class Row>
HPCPLAN_HD inline void for_each_row_around(const GridGeometry& g, double x, double y, double z,
                                           Row&& row) {
  const std::int64_t cx = cell_coordinate(g, x, 0), cy = cell_coordinate(g, y, 1),
                     cz = cell_coordinate(g, z, 2);
  const std::int64_t x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < g.n[0] ? cx + 1 : cx;
  for (std::int64_t k = cz > 0 ? cz - 1 : 0; k <= cz + 1 && k < g.n[2]; ++k)
    for (std::int64_t j = cy > 0 ? cy - 1 : 0; j <= cy + 1 && j < g.n[1]; ++j) {
      const std::int64_t first = g.n[0] * (j + g.n[1] * k);
      row(static_cast<std::uint64_t>(first + x0), static_cast<std::uint64_t>(first + x1));
    }
}

// fn(q, dx, dy, dz, r2) for every particle q with r2 = |x - x_q|^2 < support2, (dx, dy, dz) =
// x - x_q; a particle queried at its own position sees itself. row_items(first, last, visit)
// calls visit(q) for every particle q filed in cells first .. last (one x-row). Order: rows as
// for_each_row_around; within a row, the backend's order.
template <class RowItems, class Fn>
HPCPLAN_HD inline void for_each_within(const GridGeometry& g, double support2, double x, double y,
                                       double z, const double* px, const double* py,
                                       const double* pz, RowItems&& row_items, Fn&& fn) {
  for_each_row_around(g, x, y, z, [&](std::uint64_t first, std::uint64_t last) {
    row_items(first, last, [&](std::uint32_t q) {
      const double dx = x - px[q], dy = y - py[q], dz = z - pz[q];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < support2) fn(q, dx, dy, dz, r2);
    });
  });
}

}  // namespace hpcplan::sph
