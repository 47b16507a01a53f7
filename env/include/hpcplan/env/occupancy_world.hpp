#pragma once
// Seed 000's occupancy grid over the fluid (its A* world), as a World: the fluid's box is cut
// into cubes of about `cell` (0.2) on a side, aligned with the box and covering it exactly (the
// seed's own grid overhangs small boxes and misses a strip of large ones; here n = round(L /
// cell) cells per axis, of side L / n). A cell is occupied when a particle centre lies within
// `particle_radius` (0.14) of its centre, or an obstacle box grown by `box_inflation` (0.2)
// overlaps it with positive volume.
//
// Adaptive occupancy (rule = density; seed 000's future-work item 3): a cell is occupied when the
// fluid's SPH-interpolated density at its centre reaches `density_threshold`, counted in
// particle equivalents: rho(x) = sum_j W(|x - x_j|) / W(0) with the fluid's own poly6 kernel
// (sph/kernels.hpp) of support `density_support` (a lone particle on the centre counts 1). The
// defaults (support 0.28, threshold 0.42) block a lone particle out to 0.1403, the seed's 0.14 to
// within 0.3 mm ((1 - 0.14^2 / 0.28^2)^3 = 0.4219); where particles crowd, their kernels add up and
// the blocked region grows to cover the gaps between them; a higher threshold lets sparse spray
// through (above 1, no lone particle blocks at all) while the bulk stays blocked. Boxes are
// blocked as in the seed's rule.
//  - a point is free when it lies in the box and its cell is free;
//  - a segment is free when every cell whose closed box it touches is free (the exact voxel
//    walk of voxel_walk.hpp: no corner cutting);
//  - the grid graph (graph/occupancy_graph.hpp) moves between the centres of free cells.
//
// Threads: immutable once built; any number of threads may query one world at once (the check
// counter is atomic).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/env/fluid_snapshot.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

// How particles block cells: the seed's radius rule, or the interpolated density.
enum class OccupancyRule { particles, density };
std::string_view to_string(OccupancyRule r);  // "particles", "density"
// Throws InputError naming the accepted rules.
OccupancyRule parse_occupancy_rule(std::string_view name);

struct OccupancyConfig {
  double cell = 0.2;              // target cell side; the real side is L / round(L / cell)
  double particle_radius = 0.14;  // 0.7 x cell in the seed
  double box_inflation = 0.2;     // how much the seed's A* grows the obstacle boxes
  OccupancyRule rule = OccupancyRule::particles;
  double density_support = 0.28;    // rule density: the poly6 kernel's support radius
  double density_threshold = 0.42;  // rule density: particle equivalents that block a cell
};

// The rule as one word for result files: "particles", or "density:SUPPORT:THRESHOLD".
std::string occupancy_label(const OccupancyConfig& c);

class OccupancyWorld {
 public:
  static constexpr int kDim = 3;
  using Point = Vec<3>;
  using Cell = std::array<int, 3>;

  // Throws InputError for a non-positive cell or negative radius/inflation, a non-positive
  // density support or threshold, an empty domain, or a grid of more than 2^31 cells.
  OccupancyWorld(const FluidSnapshot& snapshot, const OccupancyConfig& config = {});
  // The same for another frame, reusing this world's memory.
  void rebuild(const FluidSnapshot& snapshot, const OccupancyConfig& config = {});

  Aabb<3> bounds() const { return domain_; }
  bool point_free(const Point& p) const;
  bool segment_free(const Point& a, const Point& b) const;
  // True when the closed box lies in the domain and touches only free cells.
  bool box_free(const Aabb<3>& box) const;
  std::string why_not_free(const Point& p) const;
  double free_volume() const;
  std::uint64_t collision_checks() const { return checks_.value(); }

  // The grid itself, for the grid graph and for tests.
  const std::array<int, 3>& cells_per_axis() const { return n_; }
  const Vec<3>& cell_size() const { return size_; }
  std::uint64_t cell_count() const { return occupied_.size(); }
  std::uint64_t occupied_count() const { return occupied_total_; }
  std::uint32_t index(const Cell& c) const {
    return static_cast<std::uint32_t>(c[0] +
                                      n_[0] * (c[1] + static_cast<std::int64_t>(n_[1]) * c[2]));
  }
  Cell cell_of_index(std::uint32_t i) const {
    return {static_cast<int>(i % n_[0]), static_cast<int>(i / n_[0] % n_[1]),
            static_cast<int>(i / n_[0] / n_[1])};
  }
  bool inside(const Cell& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < n_[0] && c[1] < n_[1] && c[2] < n_[2];
  }
  bool occupied(const Cell& c) const { return occupied_[index(c)] != 0; }
  bool occupied(std::uint32_t i) const { return occupied_[i] != 0; }
  // Rule density: the interpolated density at each cell's centre, in particle equivalents
  // (empty under the particles rule).
  const std::vector<float>& density() const { return density_; }
  // The cell holding p (clamped into the grid: the box's upper faces belong to the last cells).
  Cell cell_of(const Point& p) const;
  Point centre(const Cell& c) const;
  // Counts one check per cell looked up.
  void count_checks(std::uint64_t n) const { checks_.add(n); }

 private:
  Aabb<3> domain_;
  std::array<int, 3> n_{};
  Vec<3> size_{};
  std::vector<std::uint8_t> occupied_;
  std::vector<float> density_;
  std::uint64_t occupied_total_ = 0;
  CheckCounter checks_;
};

}  // namespace hpcplan::env
