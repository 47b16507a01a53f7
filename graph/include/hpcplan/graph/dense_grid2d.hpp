#pragma once
// A dense 2D occupancy grid, 8-connected: diagonal moves need both orthogonal cells free (the
// seed rule in 2D). States are flat cell indices; the same search engine runs on it unchanged.
//
// Threads: one run at a time (its check counter is a plain member).
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/uniform_grid.hpp"
#include "hpcplan/graph/lattice_cost.hpp"

namespace hpcplan {

class DenseGrid2D {
 public:
  using State = std::uint32_t;
  using Move = std::uint8_t;
  using Cost = LatticeCost;
  struct Hash {
    std::size_t operator()(State s) const noexcept { return splitmix64_mix(s); }
  };
  static constexpr Move kNoMove = 0xFF;

  DenseGrid2D(int width, int height) {
    if (width < 1 || height < 1) throw std::invalid_argument("grid must be at least 1x1");
    shape_ = GridShape<2>({width, height});
    blocked_.assign(shape_.size(), false);
  }

  int width() const { return static_cast<int>(shape_.count(0)); }
  int height() const { return static_cast<int>(shape_.count(1)); }
  State at(int x, int y) const { return static_cast<State>(shape_.index({x, y})); }
  int x_of(State s) const { return static_cast<int>(shape_.coords(s)[0]); }
  int y_of(State s) const { return static_cast<int>(shape_.coords(s)[1]); }
  void set_blocked(int x, int y, bool b) { blocked_[at(x, y)] = b; }
  bool is_free(int x, int y) const { return shape_.contains({x, y}) && !blocked_[at(x, y)]; }
  std::uint64_t collision_checks() const { return checks_; }

  template <class Emit>
  void for_each_successor(State s, Emit&& emit) const {
    const int x = x_of(s), y = y_of(s);
    bool free_axis[4];
    for (Move m = 0; m < 4; ++m) {
      ++checks_;
      free_axis[m] = is_free(x + kDx[m], y + kDy[m]);
      if (free_axis[m]) emit(at(x + kDx[m], y + kDy[m]), LatticeCost::for_axes(1), m);
    }
    for (Move m = 4; m < 8; ++m) {
      // Diagonal m combines axis moves kAxisA[m] and kAxisB[m].
      if (!free_axis[kAxisA[m]] || !free_axis[kAxisB[m]]) continue;
      ++checks_;
      if (is_free(x + kDx[m], y + kDy[m]))
        emit(at(x + kDx[m], y + kDy[m]), LatticeCost::for_axes(2), m);
    }
  }
  State predecessor(State s, Move m) const { return at(x_of(s) - kDx[m], y_of(s) - kDy[m]); }

  double checked_edge_length(State a, State b) const {
    const int ax = x_of(a), ay = y_of(a), bx = x_of(b), by = y_of(b);
    const int dx = bx - ax, dy = by - ay;
    if (dx < -1 || dx > 1 || dy < -1 || dy > 1 || (dx == 0 && dy == 0)) return -1.0;
    if (!is_free(ax, ay) || !is_free(bx, by)) return -1.0;
    if (dx != 0 && dy != 0) {
      if (!is_free(ax + dx, ay) || !is_free(ax, ay + dy)) return -1.0;
      return 1.41421356237309504880;
    }
    return 1.0;
  }

 private:
  // 0..3: -x, +x, -y, +y; 4..7: diagonals.
  static constexpr int kDx[8] = {-1, 1, 0, 0, -1, -1, 1, 1};
  static constexpr int kDy[8] = {0, 0, -1, 1, -1, 1, -1, 1};
  static constexpr int kAxisA[8] = {0, 0, 0, 0, 0, 0, 1, 1};
  static constexpr int kAxisB[8] = {0, 0, 0, 0, 2, 3, 2, 3};

  GridShape<2> shape_;
  std::vector<std::uint8_t> blocked_;
  mutable std::uint64_t checks_ = 0;
};

}  // namespace hpcplan
