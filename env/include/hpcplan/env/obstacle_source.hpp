#pragma once
// What the grid engines plan on: the GOG field they generate, or an occupancy grid a user
// brings. The sparse lattice graph, the dense engine, the distributed ranks and the reports all
// read this one handle; each asks it once which kind it holds and takes its own fast path
// (GOG's per-axis level sums, or the occupancy bits), never a per-state virtual call.
//
// A handle refers to its field; it does not own it. A GogField converts to a handle
// implicitly, so every caller that plans on GOG passes its field as before.
//
// Threads: immutable; safe for any number of concurrent readers (as the fields).
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/occupancy_grid.hpp"

namespace hpcplan {

class ObstacleSource {
 public:
  ObstacleSource(const GogField& gog) : gog_(&gog) {}  // NOLINT: implicit on purpose
  ObstacleSource(const OccupancyGrid& grid) : grid_(&grid) {}  // NOLINT

  bool is_gog() const { return gog_ != nullptr; }
  bool is_occupancy() const { return grid_ != nullptr; }
  const GogField& gog() const {
    if (!gog_) throw std::logic_error("ObstacleSource: not a GOG field");
    return *gog_;
  }
  const OccupancyGrid& occupancy() const {
    if (!grid_) throw std::logic_error("ObstacleSource: not an occupancy grid");
    return *grid_;
  }
  // The same pointers: the same field.
  const void* identity() const { return gog_ ? static_cast<const void*>(gog_) : grid_; }

  int dims() const { return gog_ ? gog_->dims() : grid_->dims(); }
  // The lattice's side: [0, extent)^d (an occupancy grid's largest side).
  int extent() const { return gog_ ? gog_->extent() : grid_->extent(); }
  // The side along one axis (extent for GOG).
  int size(int axis) const { return gog_ ? gog_->extent() : grid_->size(axis); }
  // From the GOG formula or the occupancy bits; false outside the box.
  bool is_free(std::span<const int> coords) const {
    return gog_ ? gog_->is_free(coords) : grid_->is_free(coords);
  }
  // The fraction of the lattice's cells that are blocked (an occupancy grid's cells outside
  // its shape count as blocked only in the lattice, not here: this is the array's own).
  double blocked_fraction() const {
    if (gog_) return gog_->blocked_fraction();
    return 1.0 - static_cast<double>(grid_->free_cells()) / static_cast<double>(grid_->cells());
  }
  // "gog" or the grid's format ("movingai", "voxel", "npy", "array").
  std::string kind() const { return gog_ ? "gog" : grid_->format; }

 private:
  const GogField* gog_ = nullptr;
  const OccupancyGrid* grid_ = nullptr;
};

}  // namespace hpcplan
