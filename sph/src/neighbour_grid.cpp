#include "hpcplan/sph/neighbour_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hpcplan/core/error.hpp"

namespace hpcplan::sph {

NeighbourGrid::NeighbourGrid(const Box3& region, double support)
    : region_(region), support_(support), support2_(support * support) {
  if (!(support > 0.0) || !std::isfinite(support))
    throw InputError("the neighbour grid needs a positive support radius");
  typename GridShape<3>::Coords counts{};
  for (int k = 0; k < 3; ++k) {
    const double extent = region.hi[k] - region.lo[k];
    if (!(extent >= 0.0)) throw InputError("the neighbour grid's region is inverted");
    // Whole cells no smaller than the support; the region is stretched to fill them.
    std::int64_t& n = geometry_.n[k];
    n = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(extent / support)));
    geometry_.lo[k] = region.lo[k];
    geometry_.inv_cell[k] = static_cast<double>(n) / std::max(extent, support);
    counts[k] = n;
  }
  const std::int64_t* n = geometry_.n;
  const double cells = static_cast<double>(n[0]) * n[1] * n[2];
  if (cells > 4.0e9)
    throw InputError("the neighbour grid would need " + std::to_string(cells) +
                     " cells; the region is too large for its support radius");
  shape_ = GridShape<3>(counts);
}

void NeighbourGrid::build(const Particles& p) {
  const std::size_t n = p.size();
  key_.resize(n);
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < count; ++i) key_[i] = cell_key(geometry_, p.x[i], p.y[i], p.z[i]);
  buckets_.build_from_keys(shape_.size(), key_);
}

void NeighbourGrid::sort_particles(Particles& p) {
  const auto order = buckets_.all_items();
  p.permute(order);
  std::vector<std::uint32_t> keys(key_.size());
  for (std::size_t k = 0; k < order.size(); ++k) keys[k] = key_[order[k]];
  key_.swap(keys);
  buckets_.renumber_in_bucket_order();
}

void NeighbourGrid::mark_cells_of(const Particles& p, std::uint8_t wall_flag) {
  marked_.assign(shape_.size(), 0);
  for (std::size_t i = 0; i < key_.size() && i < p.size(); ++i)
    if (p.wall[i] == wall_flag) marked_[key_[i]] = 1;
}

bool NeighbourGrid::near_marked(double x, double y, double z) const {
  bool found = false;
  for_each_row_around(geometry_, x, y, z, [&](std::uint64_t first, std::uint64_t last) {
    for (std::uint64_t c = first; c <= last && !found; ++c) found = marked_[c] != 0;
  });
  return found;
}

}  // namespace hpcplan::sph
