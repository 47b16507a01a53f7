#include "hpcplan/env/particle_world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/segment_box.hpp"
#include "hpcplan/env/voxel_walk.hpp"

namespace hpcplan::env {

namespace {
// Squared distance from c to the segment a-b.
double distance2_to_segment(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  double ab[3], ac[3], len2 = 0.0, t = 0.0;
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    len2 += ab[k] * ab[k];
    t += ab[k] * ac[k];
  }
  t = len2 > 0.0 ? std::clamp(t / len2, 0.0, 1.0) : 0.0;
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = ac[k] - t * ab[k];
    d2 += d * d;
  }
  return d2;
}
}  // namespace

ParticleWorld::ParticleWorld(const FluidSnapshot& snapshot, const ParticleWorldConfig& config) {
  rebuild(snapshot, config);
}

void ParticleWorld::rebuild(const FluidSnapshot& snapshot, const ParticleWorldConfig& config) {
  domain_ = snapshot.domain;
  radius_ = config.radius;
  boxes_.assign(snapshot.boxes.begin(), snapshot.boxes.end());
  if (!(radius_ >= 0.0) || !std::isfinite(radius_))
    throw InputError("the particle world's ball radius must be a number >= 0");
  // Cells at least a diameter wide (and not so small that empty cells dominate).
  const double cell = std::max(2.0 * radius_, 1e-3);
  for (int k = 0; k < 3; ++k) {
    const double extent = domain_.hi[k] - domain_.lo[k];
    if (!(extent > 0.0) || !std::isfinite(extent))
      throw InputError("the particle world needs a box of positive size");
    n_[k] = std::clamp(static_cast<int>(std::floor(extent / cell)), 1, 1024);
    inv_cell_[k] = n_[k] / extent;
  }
  const std::size_t cells = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
  keys_.resize(snapshot.particles.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const auto c = cell_of(snapshot.particles[i]);
    keys_[i] =
        static_cast<std::uint32_t>(c[0] + n_[0] * (c[1] + static_cast<std::size_t>(n_[1]) * c[2]));
  }
  buckets_.build_from_keys(cells, keys_);
  // Store the centres in cell order so a cell's balls are adjacent in memory.
  centres_.clear();
  centres_.reserve(keys_.size());
  for (std::uint32_t i : buckets_.all_items()) centres_.push_back(snapshot.particles[i]);
  buckets_.renumber_in_bucket_order();
}

std::array<int, 3> ParticleWorld::cell_of(const Point& p) const {
  std::array<int, 3> c;
  for (int k = 0; k < 3; ++k) {
    const double u = (p[k] - domain_.lo[k]) * inv_cell_[k];
    c[k] = u >= 0.0 ? std::min(static_cast<int>(u), n_[k] - 1) : 0;  // NaN -> 0
  }
  return c;
}

long long ParticleWorld::ball_hit(const Point& a, const Point& b) const {
  const double r2 = radius_ * radius_;
  // Short segments (every tree edge, every point test): the cells of the segment's bounding box
  // grown by the radius, read as contiguous x-runs of the CSR list.
  {
    Point lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(a[k], b[k]) - radius_;
      hi[k] = std::max(a[k], b[k]) + radius_;
    }
    const auto c0 = cell_of(lo), c1 = cell_of(hi);
    const std::size_t cells = static_cast<std::size_t>(c1[0] - c0[0] + 1) *
                              static_cast<std::size_t>(c1[1] - c0[1] + 1) *
                              static_cast<std::size_t>(c1[2] - c0[2] + 1);
    if (cells <= 512) {
      for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y) {
          const std::size_t row = n_[0] * (y + static_cast<std::size_t>(n_[1]) * z);
          for (std::uint32_t i : buckets_.items_in(row + c0[0], row + c1[0]))
            if (distance2_to_segment(a, b, centres_[i]) <= r2) return static_cast<long long>(i);
        }
      return -1;
    }
  }
  // Long segments (the smoother's): walk the cells the segment touches.
  // Balls reach at most one cell beyond the cells the segment touches (cells >= a diameter;
  // a ball filed in a cell has its centre there). Walk the segment's cells; test each cell's
  // 27-neighbourhood once, skipping cells already tested by the previous step of the walk.
  double ua[3], ub[3];
  for (int k = 0; k < 3; ++k) {
    ua[k] = std::clamp((a[k] - domain_.lo[k]) * inv_cell_[k], 0.0, static_cast<double>(n_[k]));
    ub[k] = std::clamp((b[k] - domain_.lo[k]) * inv_cell_[k], 0.0, static_cast<double>(n_[k]));
  }
  std::vector<std::uint64_t> seen;  // cells already tested
  long long hit = -1;
  auto test_cell = [&](int x, int y, int z) {
    const std::size_t c =
        static_cast<std::size_t>(x) + n_[0] * (y + static_cast<std::size_t>(n_[1]) * z);
    for (std::uint32_t i : buckets_.items_in(c))
      if (distance2_to_segment(a, b, centres_[i]) <= r2) return static_cast<long long>(i);
    return -1LL;
  };
  auto visit = [&](const int* c) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) continue;
          const std::uint64_t key =
              static_cast<std::uint64_t>(x) + n_[0] * (y + static_cast<std::uint64_t>(n_[1]) * z);
          // Consecutive cells of the walk share most of their neighbourhoods; looking back two
          // steps' worth keeps the test linear in the walk's length.
          const auto recent = seen.size() > 64 ? seen.end() - 64 : seen.begin();
          if (std::find(recent, seen.end(), key) != seen.end()) continue;
          seen.push_back(key);
          hit = test_cell(x, y, z);
          if (hit >= 0) return true;
        }
    return false;
  };
  voxel_walk(std::integral_constant<int, 3>{}, n_.data(), ua, ub, visit);
  return hit;
}

bool ParticleWorld::point_free(const Point& p) const {
  checks_.add();
  if (!domain_.contains(p)) return false;
  for (const Aabb<3>& b : boxes_)
    if (b.contains(p)) return false;
  return ball_hit(p, p) < 0;
}

bool ParticleWorld::segment_free(const Point& a, const Point& b) const {
  checks_.add();
  if (!domain_.contains(a) || !domain_.contains(b)) return false;  // the box is convex
  for (const Aabb<3>& box : boxes_)
    if (segment_hits_box<3>(a, b, box)) return false;
  return ball_hit(a, b) < 0;
}

bool ParticleWorld::box_free(const Aabb<3>& box) const {
  checks_.add();
  if (!domain_.contains(box.lo) || !domain_.contains(box.hi)) return false;
  for (const Aabb<3>& b : boxes_) {
    bool overlap = true;
    for (int k = 0; k < 3; ++k) overlap = overlap && b.lo[k] <= box.hi[k] && box.lo[k] <= b.hi[k];
    if (overlap) return false;
  }
  Vec<3> lo, hi;
  for (int k = 0; k < 3; ++k) lo[k] = box.lo[k] - radius_, hi[k] = box.hi[k] + radius_;
  const auto from = cell_of(lo), to = cell_of(hi);
  const double r2 = radius_ * radius_;
  for (int z = from[2]; z <= to[2]; ++z)
    for (int y = from[1]; y <= to[1]; ++y)
      for (int x = from[0]; x <= to[0]; ++x) {
        const std::size_t c =
            static_cast<std::size_t>(x) + n_[0] * (y + static_cast<std::size_t>(n_[1]) * z);
        for (std::uint32_t i : buckets_.items_in(c)) {
          double d2 = 0.0;
          for (int k = 0; k < 3; ++k) {
            const double v = std::clamp(centres_[i][k], box.lo[k], box.hi[k]) - centres_[i][k];
            d2 += v * v;
          }
          if (d2 <= r2) return false;
        }
      }
  return true;
}

std::string ParticleWorld::why_not_free(const Point& p) const {
  if (!domain_.contains(p)) return "outside the fluid's box";
  for (std::size_t i = 0; i < boxes_.size(); ++i)
    if (boxes_[i].contains(p)) return "inside obstacle box " + std::to_string(i);
  if (const long long i = ball_hit(p, p); i >= 0)
    return "within " + std::to_string(radius_) + " of particle " + format_point<3>(centres_[i]);
  return "";
}

double ParticleWorld::free_volume() const {
  double v = domain_.volume();
  for (const Aabb<3>& b : boxes_) v -= b.volume();
  v -= static_cast<double>(centres_.size()) * 4.0 / 3.0 * std::numbers::pi * radius_ * radius_ *
       radius_;
  return std::max(v, 0.0);
}

}  // namespace hpcplan::env
