#include "hpcplan/env/occupancy_world.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/voxel_walk.hpp"
#include "hpcplan/sph/kernels.hpp"

namespace hpcplan::env {

std::string_view to_string(OccupancyRule r) {
  return r == OccupancyRule::density ? "density" : "particles";
}

OccupancyRule parse_occupancy_rule(std::string_view name) {
  if (name == "particles") return OccupancyRule::particles;
  if (name == "density") return OccupancyRule::density;
  throw InputError("unknown occupancy rule '" + std::string(name) +
                   "' (expected particles or density)");
}

std::string occupancy_label(const OccupancyConfig& c) {
  if (c.rule == OccupancyRule::particles) return "particles";
  std::ostringstream out;  // shortest form of each number (0.28, not 0.280000)
  out << "density:" << c.density_support << ":" << c.density_threshold;
  return out.str();
}

OccupancyWorld::OccupancyWorld(const FluidSnapshot& snapshot, const OccupancyConfig& config) {
  rebuild(snapshot, config);
}

void OccupancyWorld::rebuild(const FluidSnapshot& snapshot, const OccupancyConfig& config) {
  domain_ = snapshot.domain;
  if (!(config.cell > 0.0) || !std::isfinite(config.cell))
    throw InputError("the occupancy grid's cell must be a positive number");
  if (!(config.particle_radius >= 0.0) || !(config.box_inflation >= 0.0))
    throw InputError("the occupancy grid's particle radius and box inflation must be >= 0");
  if (config.rule == OccupancyRule::density &&
      (!(config.density_support > 0.0) || !std::isfinite(config.density_support) ||
       !(config.density_threshold > 0.0) || !std::isfinite(config.density_threshold)))
    throw InputError("the density occupancy's support and threshold must be positive numbers");
  double cells = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double extent = domain_.hi[k] - domain_.lo[k];
    if (!(extent > 0.0) || !std::isfinite(extent))
      throw InputError("the occupancy grid needs a box of positive size");
    n_[k] = std::max(1, static_cast<int>(std::lround(extent / config.cell)));
    size_[k] = extent / n_[k];
    cells *= n_[k];
  }
  if (cells > 2147483648.0) throw InputError("the occupancy grid would need over 2^31 cells");
  occupied_.assign(static_cast<std::size_t>(cells), 0);

  // Visits the cells whose centre lies within r of p (centre of cell i along an axis:
  // lo + (i + 0.5) size) with their index and squared distance.
  auto for_cells_near = [&](const Vec<3>& p, double r, auto&& visit) {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const double u = (p[k] - domain_.lo[k]) / size_[k];
      lo[k] = std::max(0, static_cast<int>(std::ceil(u - r / size_[k] - 0.5)));
      hi[k] = std::min(n_[k] - 1, static_cast<int>(std::floor(u + r / size_[k] - 0.5)));
    }
    const double r2 = r * r;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const Point c = centre({x, y, z});
          const double d2 = (c[0] - p[0]) * (c[0] - p[0]) + (c[1] - p[1]) * (c[1] - p[1]) +
                            (c[2] - p[2]) * (c[2] - p[2]);
          if (d2 <= r2) visit(index({x, y, z}), d2);
        }
  };
  if (config.rule == OccupancyRule::particles) {
    density_.clear();
    for (const Vec<3>& p : snapshot.particles)
      for_cells_near(p, config.particle_radius, [&](std::uint32_t i, double) { occupied_[i] = 1; });
  } else {
    // The fluid's poly6 kernel over W(0): one particle on the centre weighs 1.
    const sph::Poly6Kernel kernel(config.density_support);
    const double w0 = kernel.w(0.0);
    density_.assign(occupied_.size(), 0.0f);
    for (const Vec<3>& p : snapshot.particles)
      for_cells_near(p, config.density_support, [&](std::uint32_t i, double d2) {
        density_[i] += static_cast<float>(kernel.w(d2) / w0);
      });
    const auto threshold = static_cast<float>(config.density_threshold);
    for (std::size_t i = 0; i < density_.size(); ++i)
      if (density_[i] >= threshold) occupied_[i] = 1;
  }
  // Boxes, grown: cells overlapping them with positive volume.
  for (const Aabb<3>& b : snapshot.boxes) {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const double a = (b.lo[k] - config.box_inflation - domain_.lo[k]) / size_[k];
      const double c = (b.hi[k] + config.box_inflation - domain_.lo[k]) / size_[k];
      // Cell i spans [i, i + 1): it overlaps (a, c) when i < c and i + 1 > a.
      lo[k] = std::max(0, static_cast<int>(std::floor(a)));
      hi[k] = std::min(n_[k] - 1, static_cast<int>(std::ceil(c)) - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) occupied_[index({x, y, z})] = 1;
  }
  occupied_total_ = 0;
  for (std::uint8_t o : occupied_) occupied_total_ += o;
}

OccupancyWorld::Cell OccupancyWorld::cell_of(const Point& p) const {
  Cell c;
  for (int k = 0; k < 3; ++k)
    c[k] =
        std::clamp(static_cast<int>(std::floor((p[k] - domain_.lo[k]) / size_[k])), 0, n_[k] - 1);
  return c;
}

OccupancyWorld::Point OccupancyWorld::centre(const Cell& c) const {
  return {domain_.lo[0] + (c[0] + 0.5) * size_[0], domain_.lo[1] + (c[1] + 0.5) * size_[1],
          domain_.lo[2] + (c[2] + 0.5) * size_[2]};
}

bool OccupancyWorld::point_free(const Point& p) const {
  checks_.add();
  return domain_.contains(p) && !occupied(cell_of(p));
}

bool OccupancyWorld::segment_free(const Point& a, const Point& b) const {
  double ua[3], ub[3];
  for (int k = 0; k < 3; ++k) {
    ua[k] = (a[k] - domain_.lo[k]) / size_[k];
    ub[k] = (b[k] - domain_.lo[k]) / size_[k];
  }
  // A point on the box's upper face maps to exactly n (in the grid); rounding in the division
  // must not push it out.
  for (int k = 0; k < 3; ++k) {
    if (a[k] == domain_.hi[k]) ua[k] = n_[k];
    if (b[k] == domain_.hi[k]) ub[k] = n_[k];
  }
  const VoxelWalk walk =
      voxel_walk(std::integral_constant<int, 3>{}, n_.data(), ua, ub, [&](const int* c) {
        return occupied_[index({c[0], c[1], c[2]})] != 0;
      });
  checks_.add(std::max<std::uint64_t>(1, walk.cells));
  return walk.free;
}

bool OccupancyWorld::box_free(const Aabb<3>& box) const {
  if (!domain_.contains(box.lo) || !domain_.contains(box.hi)) return false;
  const Cell lo = cell_of(box.lo), hi = cell_of(box.hi);
  // A face exactly on a cell boundary touches the next cell too.
  Cell from = lo, to = hi;
  for (int k = 0; k < 3; ++k) {
    if (from[k] > 0 && box.lo[k] <= domain_.lo[k] + from[k] * size_[k]) --from[k];
    if (to[k] + 1 < n_[k] && box.hi[k] >= domain_.lo[k] + (to[k] + 1) * size_[k]) ++to[k];
  }
  std::uint64_t looked = 0;
  bool free = true;
  for (int z = from[2]; z <= to[2] && free; ++z)
    for (int y = from[1]; y <= to[1] && free; ++y)
      for (int x = from[0]; x <= to[0] && free; ++x) {
        ++looked;
        free = !occupied({x, y, z});
      }
  checks_.add(looked);
  return free;
}

std::string OccupancyWorld::why_not_free(const Point& p) const {
  if (!domain_.contains(p)) return "outside the fluid's box";
  if (!occupied(cell_of(p))) return "";
  const Cell c = cell_of(p);
  return "in occupied cell (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
         std::to_string(c[2]) + ")";
}

double OccupancyWorld::free_volume() const {
  return static_cast<double>(occupied_.size() - occupied_total_) * size_[0] * size_[1] * size_[2];
}

}  // namespace hpcplan::env
