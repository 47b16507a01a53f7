#pragma once
// The fluid as a continuous world (seed 000's RRT* world): closed balls of `radius` (0.10, two
// particle radii) around the particle centres, plus the obstacle boxes (closed, not grown),
// inside the fluid's box. Point and segment tests are exact (point-to-segment distance against
// every ball that could reach the segment, the slab test against boxes), with a broad phase on
// core's uniform grid: the balls are filed by counting sort into cells at least one diameter
// wide, and a segment visits the cells its voxel walk touches and their neighbours.
//
// Threads: immutable once built; any number of threads may query one world at once (the check
// counter is atomic).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/env/fluid_snapshot.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

struct ParticleWorldConfig {
  double radius = 0.10;  // 2 x the seed's particle radius
};

class ParticleWorld {
 public:
  static constexpr int kDim = 3;
  using Point = Vec<3>;

  // Throws InputError for a negative radius or an empty domain.
  ParticleWorld(const FluidSnapshot& snapshot, const ParticleWorldConfig& config = {});
  // The same for another frame, reusing this world's memory (a replanner builds one world per
  // replan; fresh allocations of a few MB would cost page faults every time).
  void rebuild(const FluidSnapshot& snapshot, const ParticleWorldConfig& config = {});

  Aabb<3> bounds() const { return domain_; }
  bool point_free(const Point& p) const;
  bool segment_free(const Point& a, const Point& b) const;
  // True when the closed box lies in the domain, misses the obstacle boxes and keeps more than
  // the radius from every ball centre.
  bool box_free(const Aabb<3>& box) const;
  std::string why_not_free(const Point& p) const;
  // The box minus the boxes (exact) minus the balls (their volume, overlaps ignored).
  double free_volume() const;
  std::uint64_t collision_checks() const { return checks_.value(); }
  double radius() const { return radius_; }

 private:
  std::array<int, 3> cell_of(const Point& p) const;
  // The first ball within radius of segment a-b (a == b: of the point), or -1.
  long long ball_hit(const Point& a, const Point& b) const;

  Aabb<3> domain_;
  double radius_ = 0.1;
  std::array<int, 3> n_{};
  Vec<3> inv_cell_{};
  std::vector<Point> centres_;       // in cell order
  std::vector<std::uint32_t> keys_;  // build scratch
  CsrBuckets buckets_;
  std::vector<Aabb<3>> boxes_;
  CheckCounter checks_;
};

}  // namespace hpcplan::env
