#pragma once
// The fluid's occupancy grid (env/occupancy_world.hpp) as a graph for the search engine: the
// states are free cells (flat indices), 26-connected as in seed 000's A*, with costs of 1, √2
// and √3 cells (exact, LatticeCost). Where the seed only asks the target cell to be free, a move
// here needs every cell it passes to be free (the 2, 4 or 8 cells meeting at the face, edge or
// corner it crosses): the segment between the two centres then passes the world's exact voxel
// walk, so a plan never cuts a corner of an occupied cell and the smoother, which uses the same
// world, can only shorten it.
//
// Heuristics: OccupancyOctile (the exact distance of this graph with no obstacles: admissible and
// consistent) and OccupancyEuclidean (the seed's; admissible, weaker).
//
// Threads: a graph belongs to one run (its check counter is a plain member); the world it reads
// may be shared.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/graph/lattice_cost.hpp"
#include "hpcplan/graph/lattice_distance.hpp"

namespace hpcplan {

class OccupancyGraph {
 public:
  using State = std::uint32_t;
  using Move = std::uint8_t;
  using Cost = LatticeCost;
  struct Hash {
    std::size_t operator()(State s) const noexcept { return splitmix64_mix(s); }
  };
  static constexpr Move kNoMove = 0xFF;

  explicit OccupancyGraph(const env::OccupancyWorld& world) : world_(world) {
    Move m = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          moves_[m++] = {dx, dy, dz};
        }
  }

  const env::OccupancyWorld& world() const { return world_; }
  std::uint64_t collision_checks() const { return checks_; }
  // Dense range of the states, for the engine's flat visited map.
  std::uint64_t state_count() const { return world_.cell_count(); }

  template <class Emit>
  void for_each_successor(State s, Emit&& emit) const {
    // An occupied cell has no edges (D* Lite's repairs rely on edges being symmetric; A* never
    // expands one: its start is a free cell).
    ++checks_;
    if (world_.occupied(s)) return;
    const env::OccupancyWorld::Cell c = world_.cell_of_index(s);
    for (Move m = 0; m < 26; ++m) {
      const auto& d = moves_[m];
      const int axes = (d[0] != 0) + (d[1] != 0) + (d[2] != 0);
      if (move_free(c, d)) emit(world_.index(shift(c, d)), LatticeCost::for_axes(axes), m);
    }
  }
  State predecessor(State s, Move m) const {
    const auto& d = moves_[m];
    return world_.index(shift(world_.cell_of_index(s), {-d[0], -d[1], -d[2]}));
  }
  // The length (in cells) of the edge a -> b, or -1 when it is not an edge of free cells.
  double checked_edge_length(State a, State b) const {
    const auto ca = world_.cell_of_index(a), cb = world_.cell_of_index(b);
    const std::array<int, 3> d{cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]};
    if (std::abs(d[0]) > 1 || std::abs(d[1]) > 1 || std::abs(d[2]) > 1 || (!d[0] && !d[1] && !d[2]))
      return -1.0;
    if (world_.occupied(a) || !move_free(ca, d)) return -1.0;
    return LatticeCost::for_axes((d[0] != 0) + (d[1] != 0) + (d[2] != 0)).value();
  }

 private:
  static env::OccupancyWorld::Cell shift(const env::OccupancyWorld::Cell& c,
                                         const std::array<int, 3>& d) {
    return {c[0] + d[0], c[1] + d[1], c[2] + d[2]};
  }
  // Every cell c + (any subset of d's non-zero axes) inside the grid and free.
  bool move_free(const env::OccupancyWorld::Cell& c, const std::array<int, 3>& d) const {
    if (!world_.inside(shift(c, d))) return false;
    for (int mask = 1; mask < 8; ++mask) {
      if (((mask & 1) && !d[0]) || ((mask & 2) && !d[1]) || ((mask & 4) && !d[2])) continue;
      const env::OccupancyWorld::Cell p{c[0] + ((mask & 1) ? d[0] : 0),
                                        c[1] + ((mask & 2) ? d[1] : 0),
                                        c[2] + ((mask & 4) ? d[2] : 0)};
      ++checks_;
      if (world_.occupied(p)) return false;
    }
    return true;
  }

  const env::OccupancyWorld& world_;
  std::array<std::array<int, 3>, 26> moves_{};
  mutable std::uint64_t checks_ = 0;
};

// |delta| per axis between a cell and the goal cell.
inline std::array<int, 3> occupancy_delta(const env::OccupancyWorld& w, std::uint32_t s,
                                          std::uint32_t goal) {
  const auto a = w.cell_of_index(s), b = w.cell_of_index(goal);
  return {std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])};
}

struct OccupancyOctile {
  const env::OccupancyWorld& world;
  std::uint32_t goal;
  LatticeCost operator()(std::uint32_t s) const {
    const auto d = occupancy_delta(world, s, goal);
    return full_connectivity_free_distance(d);
  }
};

struct OccupancyEuclidean {
  const env::OccupancyWorld& world;
  std::uint32_t goal;
  double operator()(std::uint32_t s) const {
    const auto d = occupancy_delta(world, s, goal);
    return euclidean_distance(d);
  }
};

}  // namespace hpcplan
