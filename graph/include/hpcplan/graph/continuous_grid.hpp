#pragma once
// A D-dimensional grid laid over a continuous world (3D box maps, the 2D sphere world) for the
// search engine: lattice vertices every `resolution` from the world's lower corner, connected
// to all 3^D - 1 neighbours (26 in 3D, 8 in 2D), plus the exact start and goal points, which
// join the vertices of the 4^D block around them. Every edge is decided by the world's exact
// segment test, so an edge never crosses a wall thinner than a cell. A closed cell found free
// of obstacles (cached per cell) settles all edges inside it without a segment test.
//
// A move is the parent state itself: any-angle searches (Lazy Theta*) give a state a parent
// that is not its neighbour, and the hybrid's sampled states have no lattice direction.
//
// Threads: a grid belongs to one run (it caches cell tests and draws samples in const
// methods); the world it reads may be shared by several runs.
//
// Optionally, every expansion also draws `samples_per_expansion` uniform points and adds the
// nearest one it can reach as a new state (the seed 003 hybrid's RRT-style successors).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan {

template <env::World W>
class ContinuousGrid {
 public:
  static constexpr int D = W::kDim;
  using Point = env::Vec<D>;
  using State = std::uint64_t;
  using Move = std::uint64_t;
  using Cost = double;
  struct Hash {
    std::size_t operator()(State s) const noexcept { return splitmix64_mix(s); }
  };
  static constexpr Move kNoMove = ~std::uint64_t{0};
  static constexpr State kStart = std::uint64_t{1} << 62;
  static constexpr State kGoal = kStart + 1;
  static constexpr State kFirstSample = std::uint64_t{1} << 61;

  struct Config {
    double resolution = 0.1;
    int samples_per_expansion = 0;  // hybrid successors; 0 = a plain grid
    std::uint64_t seed = 1;
    std::uint64_t max_cached_cells = std::uint64_t{1} << 26;
  };

  ContinuousGrid(const W& world, const Point& start, const Point& goal, const Config& config)
      : world_(world),
        start_(start),
        goal_(goal),
        res_(config.resolution),
        samples_per_expansion_(config.samples_per_expansion),
        rng_(config.seed) {
    if (!(res_ > 0) || !std::isfinite(res_))
      throw InputError("the resolution must be a positive number");
    const auto box = world.bounds();
    lo_ = box.lo;
    double vertices = 1.0, cells = 1.0;
    Coords n, cell_counts;
    for (int k = 0; k < D; ++k) {
      const double extent = box.hi[k] - box.lo[k];
      if (res_ > extent)
        throw InputError("the resolution is coarser than the world along axis " +
                         std::string(1, "xyz"[k]));
      n[k] = static_cast<std::int64_t>(std::floor(extent / res_ * (1 + 1e-12))) + 1;
      cell_counts[k] = n[k] - 1;
      vertices *= static_cast<double>(n[k]);
      cells *= static_cast<double>(n[k] - 1);
    }
    if (vertices > 1e18) throw InputError("the resolution is too fine for this world");
    vertices_ = GridShape<D>(n);
    cells_ = GridShape<D>(cell_counts);
    if (cells <= static_cast<double>(config.max_cached_cells))
      cell_state_.assign(static_cast<std::size_t>(cells), kUnknown);
    // Neighbour offsets and their lengths.
    offsets_ = GridShape<D>::neighbour_offsets();
    for (const auto& d : offsets_) {
      int nonzero = 0;
      for (int k = 0; k < D; ++k) nonzero += d[k] != 0;
      lengths_.push_back(res_ * std::sqrt(static_cast<double>(nonzero)));
    }
    start_near_ = neighbourhood(start_);
    goal_near_ = neighbourhood(goal_);
    goal_clearance_ = std::numeric_limits<double>::infinity();
    for_each_vertex(goal_near_, [&](const Coords& c) {
      goal_clearance_ = std::min(goal_clearance_, env::distance<D>(point(index(c)), goal_));
    });
  }

  const W& world() const { return world_; }
  double resolution() const { return res_; }
  const Point& start_point() const { return start_; }
  const Point& goal_point() const { return goal_; }
  std::uint64_t vertex_count() const { return vertices_.size(); }
  // This thread's checks: the world may be shared with other planning threads.
  std::uint64_t collision_checks() const { return CheckCounter::this_thread(); }
  std::size_t samples() const { return samples_.size(); }

  Point point(State s) const {
    if (s == kStart) return start_;
    if (s == kGoal) return goal_;
    if (s >= kFirstSample) return samples_[s - kFirstSample];
    return vertex_point(coords(s));
  }

  State predecessor(State, Move m) const { return m; }

  // A lower bound on the cost from s to the goal for grid searches: a lattice vertex must
  // walk lattice moves (the octile distance, in D dimensions) to a vertex next to the goal and
  // then go straight; this is far tighter than the straight line, and still consistent.
  double lattice_heuristic(State s) const {
    if (s == kGoal) return 0.0;
    if (s >= kFirstSample || s == kStart) return env::distance<D>(point(s), goal_);
    const Coords c = coords(s);
    std::array<double, D> d;
    for (int k = 0; k < D; ++k)
      d[k] = static_cast<double>(
          std::max<std::int64_t>({0, goal_near_.lo[k] - c[k], c[k] - goal_near_.hi[k]}));
    std::sort(d.begin(), d.end(), std::greater<>());
    double h = 0.0;
    for (int i = 0; i < D; ++i) h += (d[i] - (i + 1 < D ? d[i + 1] : 0.0)) * kRoot[i];
    return h * res_ + goal_clearance_;
  }
  double distance(State a, State b) const { return env::distance<D>(point(a), point(b)); }
  bool line_of_sight(State a, State b) const { return world_.segment_free(point(a), point(b)); }

  // The independent check for returned paths: the exact segment test, never the cell cache.
  double checked_edge_length(State a, State b) const {
    const Point pa = point(a), pb = point(b);
    return world_.segment_free(pa, pb) ? env::distance<D>(pa, pb) : -1.0;
  }

  template <class Emit>
  void for_each_successor(State s, Emit&& emit) const {
    const bool on_lattice = s < kFirstSample;
    const Coords c = on_lattice ? coords(s) : Coords{};
    const Point p = on_lattice ? vertex_point(c) : point(s);
    if (on_lattice) {
      for (std::size_t i = 0; i < offsets_.size(); ++i) {
        std::array<std::int64_t, D> t;
        bool inside = true;
        for (int k = 0; k < D; ++k) {
          t[k] = c[k] + offsets_[i][k];
          inside &= t[k] >= 0 && t[k] < vertices_.count(k);
        }
        if (inside && lattice_edge_free(c, t, p)) emit(index(t), lengths_[i], s);
      }
      if (near(c, goal_near_) && world_.segment_free(p, goal_))
        emit(kGoal, env::distance<D>(p, goal_), s);
      if (near(c, start_near_) && world_.segment_free(p, start_))
        emit(kStart, env::distance<D>(p, start_), s);
    } else {
      // Off the lattice (start, goal, a sample): the vertices around it, and the goal directly.
      const auto box = neighbourhood(p);
      for_each_vertex(box, [&](const std::array<std::int64_t, D>& t) {
        const State v = index(t);
        const Point q = point(v);
        if (world_.segment_free(p, q)) emit(v, env::distance<D>(p, q), s);
      });
      if (s != kGoal && world_.segment_free(p, goal_)) emit(kGoal, env::distance<D>(p, goal_), s);
    }
    if (samples_per_expansion_ > 0 && s != kGoal) sample_successor(s, p, emit);
  }

 private:
  static constexpr std::uint8_t kUnknown = 0, kClear = 1, kBlocked = 2;
  static constexpr double kRoot[4] = {1.0, 1.4142135623730951, 1.7320508075688772, 2.0};
  using Coords = std::array<std::int64_t, D>;
  struct Range {
    Coords lo, hi;
  };

  Coords coords(State s) const { return vertices_.coords(s); }
  Point vertex_point(const Coords& c) const {
    Point p;
    for (int k = 0; k < D; ++k) p[k] = lo_[k] + static_cast<double>(c[k]) * res_;
    return p;
  }

  State index(const Coords& c) const { return vertices_.index(c); }

  // The vertices of the 4^D block around a point (its cell's corners and one ring more).
  Range neighbourhood(const Point& p) const {
    Range r;
    for (int k = 0; k < D; ++k) {
      const double x = (p[k] - lo_[k]) / res_;
      const auto f =
          std::isfinite(x) ? static_cast<std::int64_t>(std::floor(std::clamp(x, -2.0, 1e18))) : 0;
      r.lo[k] = std::clamp<std::int64_t>(f - 1, 0, vertices_.count(k) - 1);
      r.hi[k] = std::clamp<std::int64_t>(f + 2, 0, vertices_.count(k) - 1);
    }
    return r;
  }
  static bool near(const Coords& c, const Range& r) {
    for (int k = 0; k < D; ++k)
      if (c[k] < r.lo[k] || c[k] > r.hi[k]) return false;
    return true;
  }
  template <class Fn>
  static void for_each_vertex(const Range& r, Fn&& fn) {
    GridShape<D>::for_each_in(r.lo, r.hi, fn);
  }

  // The edge c->t lies in the closed cell whose lower corner is min(c, t) on each axis it
  // moves along (and c, or c - 1 at the upper face, on the others).
  bool lattice_edge_free(const Coords& c, const Coords& t, const Point& p) const {
    if (!cell_state_.empty()) {
      Coords lower;
      for (int k = 0; k < D; ++k) {
        lower[k] = std::min(c[k], t[k]);
        if (lower[k] == cells_.count(k)) --lower[k];
      }
      std::uint8_t& state = cell_state_[cells_.index(lower)];
      if (state == kUnknown) {
        env::Aabb<D> box;
        for (int k = 0; k < D; ++k) {
          box.lo[k] = lo_[k] + static_cast<double>(lower[k]) * res_;
          box.hi[k] = lo_[k] + static_cast<double>(lower[k] + 1) * res_;
        }
        state = world_.box_free(box) ? kClear : kBlocked;
      }
      if (state == kClear) return true;
    }
    return world_.segment_free(p, vertex_point(t));
  }

  template <class Emit>
  void sample_successor(State s, const Point& p, Emit& emit) const {
    const auto box = world_.bounds();
    double best = std::numeric_limits<double>::infinity();
    Point chosen{};
    for (int i = 0; i < samples_per_expansion_; ++i) {
      Point q;
      for (int k = 0; k < D; ++k) q[k] = box.lo[k] + rng_.next_unit() * (box.hi[k] - box.lo[k]);
      const double d = env::distance<D>(p, q);
      // segment_free covers q's own freedom: its end is part of the segment.
      if (d < best && world_.segment_free(p, q)) best = d, chosen = q;
    }
    if (!std::isfinite(best)) return;
    samples_.push_back(chosen);
    emit(kFirstSample + samples_.size() - 1, best, s);
  }

  const W& world_;
  Point start_, goal_;
  double res_;
  Point lo_;
  GridShape<D> vertices_;  // the lattice's vertices
  GridShape<D> cells_;     // the cells between them (one fewer per axis)
  std::vector<std::array<int, D>> offsets_;
  std::vector<double> lengths_;
  Range start_near_, goal_near_;
  double goal_clearance_ = 0.0;  // nearest vertex of the goal's block to the goal
  mutable std::vector<std::uint8_t> cell_state_;
  int samples_per_expansion_;
  mutable SplitMix64 rng_;
  mutable std::vector<Point> samples_;
};

// Straight-line distance to the goal point: admissible and consistent, since every edge
// costs its Euclidean length; the heuristic of any-angle search.
template <class Grid>
struct EuclideanToGoal {
  const Grid* grid;
  double operator()(typename Grid::State s) const {
    return env::distance<Grid::D>(grid->point(s), grid->goal_point());
  }
};

// The grid searches' heuristic (ContinuousGrid::lattice_heuristic).
template <class Grid>
struct LatticeToGoal {
  const Grid* grid;
  double operator()(typename Grid::State s) const { return grid->lattice_heuristic(s); }
};

}  // namespace hpcplan
