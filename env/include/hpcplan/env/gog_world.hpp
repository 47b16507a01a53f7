#pragma once
// The GOG field (gog.hpp) as a continuous world, so that every planner that takes a world
// (RRT, RRT-Connect, RRT*, Lazy Theta*'s segment tests, the tightener, OMPL's planners through
// sampling/world_space.hpp) plans on GOG with the same rules as on box maps and sphere worlds:
//  - the world is the closed box [0, extent]^d;
//  - the cell of a point is floor(x) per axis, the upper bound x = extent belonging to the last
//    cell; a point is free when its cell is;
//  - a segment is free when every cell whose closed box it touches is free: an exact voxel walk
//    (Amanatides-Woo in d dimensions) that, where the segment crosses an edge or corner of
//    several cells at once, checks every cell meeting there. Touching counts, so a segment can
//    never slip between two blocked cells sharing only a corner: the lattice's no-corner-cutting
//    rule. It needs no sampling resolution and cannot miss a thin corner between samples;
//  - every point test counts one collision check and a segment counts the cells it looked up.
// Lattice cell c maps to the continuous cell centre c + 0.5.
//
// The free functions work on any number of dimensions (1..16); GogWorld<D> is the World
// concept's face of them for a dimension known at compile time.
//
// Threads: immutable once built; any number of threads may query one world at once (the check
// counter is atomic).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

inline constexpr int kGogMaxDims = 16;

// True when x (field.dims() coordinates) lies in the box and its cell is free. Counts nothing.
bool gog_point_free(const GogField& field, const double* x);

// The lattice cell holding x, clamped into the box.
std::vector<int> gog_cell_of(const GogField& field, const double* x);

struct GogSegmentWalk {
  bool free = true;
  double blocked_at = 1.0;  // when not free: the segment parameter of the first blocked touch
  std::uint64_t cells = 0;  // cells looked up
};

// The voxel walk from a to b. A segment with an end outside the box is blocked at t = 0.
// Throws RunError for more than kGogMaxDims dimensions.
GogSegmentWalk gog_walk_segment(const GogField& field, const double* a, const double* b);

// Why x is not free ("outside the box", "in blocked cell (3, 7)"); empty when free.
std::string gog_why_not_free(const GogField& field, const double* x);

// The free volume of the box, exact (the field knows its blocked fraction exactly).
double gog_free_volume(const GogField& field);

template <int D>
class GogWorld {
 public:
  static constexpr int kDim = D;
  using Point = Vec<D>;

  // Throws InputError when the field's dimension is not D.
  explicit GogWorld(std::shared_ptr<const GogField> field);

  Aabb<D> bounds() const {
    Aabb<D> box;
    box.lo.fill(0.0);
    box.hi.fill(static_cast<double>(field_->extent()));
    return box;
  }
  bool point_free(const Point& p) const {
    checks_.add();
    return gog_point_free(*field_, p.data());
  }
  bool segment_free(const Point& a, const Point& b) const { return !first_contact(a, b); }
  // The segment parameter where a -> b first touches a blocked cell; empty when it never does.
  std::optional<double> first_contact(const Point& a, const Point& b) const {
    const GogSegmentWalk walk = gog_walk_segment(*field_, a.data(), b.data());
    checks_.add(walk.cells);
    if (walk.free) return std::nullopt;
    return walk.blocked_at;
  }
  std::string why_not_free(const Point& p) const { return gog_why_not_free(*field_, p.data()); }
  double free_volume() const { return gog_free_volume(*field_); }
  std::uint64_t collision_checks() const { return checks_.value(); }
  // The counter itself, for planners that test cells of the same field directly (the lattice
  // search) and add their checks to the world's.
  const CheckCounter& check_counter() const { return checks_; }

  const GogField& field() const { return *field_; }
  const std::shared_ptr<const GogField>& field_ptr() const { return field_; }

 private:
  std::shared_ptr<const GogField> field_;
  CheckCounter checks_;
};

void require_gog_dims(const GogField& field, int dims);  // InputError on a mismatch

template <int D>
GogWorld<D>::GogWorld(std::shared_ptr<const GogField> field) : field_(std::move(field)) {
  require_gog_dims(*field_, D);
}

}  // namespace hpcplan::env
