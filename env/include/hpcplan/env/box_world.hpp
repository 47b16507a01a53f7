#pragma once
// A 3D world of axis-aligned boxes (seeds 001 and 004): a boundary box and closed blocks.
// Segment queries go through a uniform bucket grid so a short edge meets only the few blocks
// near it; every candidate is then decided exactly by the slab test.
//
// Threads: immutable once built; any number of threads may query one world at once (the check
// counter is atomic).
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

struct Block {
  Aabb<3> box;
  std::array<double, 3> rgb{0.5, 0.5, 0.5};
  int line = 0;  // line of the map file it came from (0 when built in code)
};

// Blocks are closed, and padded by kContactMargin times the boundary's largest side: a path
// that would only graze a block once its decimal coordinates are rounded to doubles (a wall
// face at 15.1 is stored as 15.0999999999999996) counts as touching it, so no point of an
// accepted segment, however it is rounded, lies in a block.
inline constexpr double kContactMargin = 1e-9;

class BoxWorld {
 public:
  static constexpr int kDim = 3;
  using Point = Vec<3>;

  // Throws InputError for an empty or inverted boundary or block.
  BoxWorld(Aabb<3> boundary, std::vector<Block> blocks);

  const Aabb<3>& bounds() const { return boundary_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  std::array<double, 3> boundary_rgb{0.0, 0.0, 0.0};

  bool point_free(const Point& p) const;
  // True when the closed segment stays inside the boundary and meets no block.
  bool segment_free(const Point& a, const Point& b) const;
  // True when the closed box lies inside the boundary and meets no block.
  bool box_free(const Aabb<3>& box) const;
  // Why `p` is not free ("outside the boundary", "inside the block of line 7"); empty if free.
  std::string why_not_free(const Point& p) const;

  double free_volume() const { return free_volume_; }  // estimated, within ~1%
  std::uint64_t collision_checks() const { return checks_.value(); }

 private:
  template <class Visit>
  bool any_candidate(const Aabb<3>& region, Visit&& visit) const;

  Aabb<3> boundary_;
  std::vector<Block> blocks_;
  std::vector<Aabb<3>> boxes_;  // blocks_[i].box padded by the contact margin, packed
  // Bucket grid: bucket b lists the blocks whose closed box overlaps it.
  UniformGrid<3> buckets_;
  CsrBuckets bucket_items_;
  double free_volume_ = 0.0;
  CheckCounter checks_;  // shared by concurrent readers
};

}  // namespace hpcplan::env
