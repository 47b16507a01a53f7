#pragma once
// Neighbour search on a cell grid (core/uniform_grid.hpp): cells at least one support radius
// wide cover the region the particles live in, each substep lists the particles per cell by
// counting sort into CSR (no per-cell vectors), and the neighbours of a point are found in the
// 27 cells around its own. Cells are numbered x fastest, so the three cells of one x-row are
// one contiguous run of the CSR list: a query reads 9 runs, not 27 buckets.
//
// Threads: build() from one thread (it runs its own parallel loop); queries are const and may
// run from any number of threads.
#include <cstdint>
#include <span>
#include <vector>

#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/sph/particles.hpp"
#include "hpcplan/sph/vec3.hpp"

namespace hpcplan::sph {

class NeighbourGrid {
 public:
  NeighbourGrid() = default;
  // `region`: where every particle lies (a particle outside is filed in the nearest border
  // cell, which keeps the search correct but slow). InputError for a non-positive support.
  NeighbourGrid(const Box3& region, double support);

  void build(const Particles& p);

  // fn(j, dx, dy, dz, r2) for every particle j with r2 = |x - x_j|^2 < support^2, where
  // (dx, dy, dz) = x - x_j; a particle queried at its own position sees itself (r2 = 0).
  // Order: cells by z, then y, then x; particles within a cell in increasing index.
  template <class Fn>
  void for_each_within(double x, double y, double z, const Particles& p, Fn&& fn) const {
    const std::int64_t cx = cell_coordinate(x, 0), cy = cell_coordinate(y, 1),
                       cz = cell_coordinate(z, 2);
    const std::int64_t x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < n_[0] ? cx + 1 : cx;
    const double* px = p.x.data();  // plain pointers: the loop below is the hot one
    const double* py = p.y.data();
    const double* pz = p.z.data();
    for (std::int64_t k = cz > 0 ? cz - 1 : 0; k <= cz + 1 && k < n_[2]; ++k)
      for (std::int64_t j = cy > 0 ? cy - 1 : 0; j <= cy + 1 && j < n_[1]; ++j) {
        const std::uint64_t row = static_cast<std::uint64_t>(n_[0]) * (j + n_[1] * k);
        const std::span<const std::uint32_t> run = buckets_.items_in(row + x0, row + x1);
        if (run.empty()) continue;
        for (const std::uint32_t q : run) {
          const double dx = x - px[q], dy = y - py[q], dz = z - pz[q];
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 < support2_) fn(q, dx, dy, dz, r2);
        }
      }
  }

  // Reorders the particles by cell (Particles::permute with cell_order()) and renumbers the
  // grid to match, so that it need not be rebuilt: afterwards the particles of a run of cells
  // are consecutive in memory.
  void sort_particles(Particles& p);

  // Marks the cells holding particles whose `wall` flag is `wall_flag` (after build()), so
  // that near_marked() can tell whether a point has any such particle within reach: the
  // water preset's walls skip the pressure extrapolation where no fluid is near.
  void mark_cells_of(const Particles& p, std::uint8_t wall_flag);
  bool near_marked(double x, double y, double z) const;

  // Particle indices in cell order, for Particles::permute: after the permutation, the
  // particles of a cell (and of a whole x-row) are adjacent in memory.
  std::span<const std::uint32_t> cell_order() const { return buckets_.all_items(); }

  double support() const { return support_; }
  // Cells per axis, and cells per unit length per axis (a GPU backend builds the same grid).
  const std::array<std::int64_t, 3>& cells_per_axis() const { return n_; }
  const Vec3& inverse_cell() const { return inv_cell_; }
  std::uint64_t cells() const { return shape_.size(); }
  const Box3& region() const { return region_; }

 private:
  std::int64_t cell_coordinate(double v, int k) const {
    const double c = (v - region_.lo[k]) * inv_cell_[k];
    if (!(c >= 0.0)) return 0;  // also NaN
    const std::int64_t i = static_cast<std::int64_t>(c);
    return i < n_[k] ? i : n_[k] - 1;
  }

  Box3 region_{};
  double support_ = 0.0, support2_ = 0.0;
  Vec3 inv_cell_{};
  std::array<std::int64_t, 3> n_{};
  GridShape<3> shape_;
  std::vector<std::uint32_t> key_;  // cell of each particle
  CsrBuckets buckets_;              // particle indices per cell
  std::vector<std::uint8_t> marked_;
};

}  // namespace hpcplan::sph
