#pragma once
// Neighbour search on a cell grid (core/uniform_grid.hpp): cells at least one support radius
// wide cover the region the particles live in, each substep lists the particles per cell by
// counting sort into CSR (no per-cell vectors), and the neighbours of a point are found in the
// 27 cells around its own. Cells are numbered x fastest (physics/grid_walk.hpp, shared with
// the GPU), so the three cells of one x-row are one contiguous run of the CSR list: a query
// reads 9 runs, not 27 buckets.
//
// Threads: build() from one thread (it runs its own parallel loop); queries are const and may
// run from any number of threads.
#include <cstdint>
#include <span>
#include <vector>

#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/sph/particles.hpp"
#include "hpcplan/sph/physics/grid_walk.hpp"
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
    // The walk is physics/grid_walk.hpp's, shared with the GPU; a row's particles are one run
    // of the CSR list.
    sph::for_each_within(
        geometry_, support2_, x, y, z, p.x.data(), p.y.data(), p.z.data(),
        [&](std::uint64_t first, std::uint64_t last, auto&& visit) {
          for (const std::uint32_t q : buckets_.items_in(first, last)) visit(q);
        },
        fn);
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
  // The cells' geometry (a GPU backend builds the same grid from it).
  const GridGeometry& geometry() const { return geometry_; }
  const Box3& region() const { return region_; }
  std::uint64_t cells() const { return shape_.size(); }

 private:
  Box3 region_{};
  double support_ = 0.0, support2_ = 0.0;
  GridGeometry geometry_;
  GridShape<3> shape_;
  std::vector<std::uint32_t> key_;  // cell of each particle
  CsrBuckets buckets_;              // particle indices per cell
  std::vector<std::uint8_t> marked_;
};

}  // namespace hpcplan::sph
