#pragma once
// Each particle's neighbours, listed once per substep from the cell grid and then read by every
// pass of that substep: a pass over a list visits only the particles within the support,
// where a pass over the 27 cells tests every candidate in them (about six per neighbour with
// cells one support wide). A particle with more neighbours than the list holds is marked and
// its passes fall back to the grid, so the capacity bounds memory, never correctness.
//
// Threads: build() runs its own parallel loop; for_each() is const and may run from any
// number of threads.
#include <cstdint>
#include <vector>

#include "hpcplan/sph/neighbour_grid.hpp"
#include "hpcplan/sph/particles.hpp"

namespace hpcplan::sph {

class NeighbourLists {
 public:
  explicit NeighbourLists(std::uint32_t capacity = 96) : capacity_(capacity) {}

  // Lists the neighbours (itself excluded) of every particle i with wanted(i): every particle
  // j within the grid's support with keep(i, j) (the pairs some phase reads; a phase must
  // skip the others itself, as it does when a list overflows to the grid). for_each then
  // reports those within `cutoff` (no more than the grid's support) of where they are now:
  // with a grid wider than the cutoff by a skin, a list stays complete while no particle has
  // moved more than half the skin (Verlet lists).
  template <class Wanted, class Keep>
  void build(const NeighbourGrid& grid, const Particles& p, double cutoff, Wanted&& wanted,
             Keep&& keep) {
    cutoff2_ = cutoff * cutoff;
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
    count_.resize(p.size());
    items_.resize(p.size() * capacity_);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      if (!wanted(static_cast<std::size_t>(i))) {
        count_[i] = 0;
        continue;
      }
      std::uint32_t* out = items_.data() + static_cast<std::size_t>(i) * capacity_;
      std::uint32_t c = 0;
      grid.for_each_within(
          p.x[i], p.y[i], p.z[i], p, [&](std::uint32_t j, double, double, double, double) {
            if (j == static_cast<std::uint32_t>(i) || !keep(static_cast<std::size_t>(i), j)) return;
            if (c < capacity_) out[c] = j;
            ++c;
          });
      count_[i] = c;
    }
  }

  // fn(j, dx, dy, dz, r2) for every neighbour j of particle i (itself excluded), (dx, dy, dz)
  // = x_i - x_j, in the grid's order.
  template <class Fn>
  void for_each(std::size_t i, const NeighbourGrid& grid, const Particles& p, Fn&& fn) const {
    const std::uint32_t c = count_[i];
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
    if (c > capacity_) {  // overflowed: ask the grid
      grid.for_each_within(xi, yi, zi, p,
                           [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                             if (j != static_cast<std::uint32_t>(i) && r2 < cutoff2_)
                               fn(j, dx, dy, dz, r2);
                           });
      return;
    }
    const std::uint32_t* list = items_.data() + i * capacity_;
    const double* px = p.x.data();
    const double* py = p.y.data();
    const double* pz = p.z.data();
    for (std::uint32_t k = 0; k < c; ++k) {
      const std::uint32_t j = list[k];
      const double dx = xi - px[j], dy = yi - py[j], dz = zi - pz[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < cutoff2_) fn(j, dx, dy, dz, r2);
    }
  }

  std::uint32_t capacity() const {
    return capacity_;
  }
  static std::uint64_t bytes_for(std::uint64_t particles, std::uint32_t capacity) {
    return particles * (capacity + 1) * 4;
  }

 private:
  std::uint32_t capacity_;
  double cutoff2_ = 0.0;
  std::vector<std::uint32_t> count_;
  std::vector<std::uint32_t> items_;  // particle i's list: items_[i * capacity_ ...]
};

}  // namespace hpcplan::sph
