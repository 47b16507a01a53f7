#pragma once
// Jump point search (Harabor and Grastien, AAAI 2011) written as a graph, so the one best-first
// engine runs it: the vertices are the jump points of a 2D lattice under the seed rule (8 moves;
// a diagonal needs both one-axis neighbours free, so no corner is cut), and an edge is a straight
// or diagonal run of free cells between two of them. A* on this graph returns the lattice's
// optimal cost while expanding only the cells where an optimal path may turn.
//
// Pruning, for the no-corner-cutting rule. A state reached by a diagonal step has no forced
// neighbours: every other neighbour is reached strictly cheaper from its parent through one of
// the two one-axis cells the step needed free. A state n reached by a straight step along an
// axis from p has a forced side when the side cell next to n is free and the one next to p is
// blocked (p could otherwise have stepped there diagonally). Where neither holds, successors that
// the parent reaches at equal or lower cost are pruned, preferring diagonal-first paths. So
//   - a straight run stops at the goal or at a cell with a forced side;
//   - a diagonal run stops at the goal or at a cell from which one of its two straight runs
//     stops somewhere;
//   - a jump point reached straight continues straight, plus, per forced side, one step to that
//     side and the diagonal towards it; reached diagonally, its two straight runs and the
//     diagonal; the start, all eight directions.
// A pruned expansion depends on how the state was reached, so the engine hands over the move
// that reached it (for_each_successor_after).
//
// Moves carry the direction and the run's length, so parents are recovered without storing
// states, and returned paths are re-validated cell by cell (checked_edge_length) through the
// cells' independent test. unit_steps() turns a path of jump points into lattice moves.
//
// Cells: int extent() (a square extent x extent box), bool free(x, y) for in-box cells (the fast
// test), bool checked_free(x, y) (an independent one, for validation).
//
// Threads: a graph belongs to one run (its check counter is a plain member).
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <stdexcept>
#include <vector>

#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/occupancy_grid.hpp"
#include "hpcplan/graph/lattice_cost.hpp"
#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan {

// The 2D cells of a GOG field: free where the two axes' levels sum below the threshold.
class GogCells2D {
 public:
  explicit GogCells2D(const GogField& field)
      : field_(field),
        x_levels_(field.level_table(0)),
        y_levels_(field.level_table(1)),
        threshold_(field.threshold()),
        extent_(field.extent()) {
    if (field.dims() != 2) throw std::logic_error("GogCells2D: the field must be 2D");
  }
  int extent() const { return extent_; }
  [[gnu::always_inline]] bool free(int x, int y) const {
    return x_levels_[x] + y_levels_[y] < threshold_;
  }
  // From the GOG formula, not the level tables.
  bool checked_free(int x, int y) const {
    const int c[2] = {x, y};
    return field_.is_free(std::span<const int>(c, 2));
  }

 private:
  const GogField& field_;
  const std::uint8_t* x_levels_;
  const std::uint8_t* y_levels_;
  int threshold_;
  int extent_;
};

// The cells of a 2D occupancy grid: one bit each. Cells past the grid's sides (inside the
// square lattice of its larger side) are blocked.
//
// A straight jump scans its line a word at a time (the "block-based" jumps of Harabor and
// Grastien, ICAPS 2014): 64 cells of the line and of its two side lines are read at once, a
// forced side is a side cell free whose predecessor along the run is blocked (side & ~shifted
// side), and the first blocked cell, forced cell or the goal ends the run. Along x the lines are
// the grid's rows; along y the sealed grid's columns (OccupancyGrid::transposed); an unsealed
// grid scans along y cell by cell.
class OccupancyCells2D {
 public:
  explicit OccupancyCells2D(const OccupancyGrid& grid)
      : grid_(grid),
        words_(grid.words()),
        word_count_(grid.word_count()),
        row_bits_(grid.dims() == 2 ? static_cast<std::uint64_t>(grid.stride(1)) : 0),
        width_(static_cast<unsigned>(grid.size(0))),
        height_(grid.dims() == 2 ? static_cast<unsigned>(grid.size(1)) : 0),
        extent_(grid.extent()) {
    if (grid.dims() != 2) throw std::logic_error("OccupancyCells2D: the grid must be 2D");
  }
  int extent() const { return extent_; }
  [[gnu::always_inline]] bool free(int x, int y) const {
    if (static_cast<unsigned>(x) >= width_ || static_cast<unsigned>(y) >= height_) return false;
    const std::uint64_t bit = static_cast<std::uint64_t>(y) * row_bits_ + static_cast<unsigned>(x);
    return (words_[bit >> 6] >> (bit & 63)) & 1;
  }
  // The grid's own cell test (coordinates, not this class's bit arithmetic).
  bool checked_free(int x, int y) const {
    const int c[2] = {x, y};
    return grid_.is_free(std::span<const int>(c, 2));
  }

  // The straight run from (a, b) along Axis (a the coordinate along it, b across) in direction
  // s: the number of steps to the first cell that is the goal (goal_a, on this line when
  // goal_on_line) or has a forced side, or 0 if a blocked cell or the edge comes first. `cells`
  // grows by the cells the scan covered (the collision checks it stands for).
  template <int Axis>
  [[gnu::always_inline]] int scan(int a, int b, int s, bool goal_on_line, int goal_a,
                                  std::uint64_t& cells) const {
    if (Axis == 1 && grid_.transposed().empty())
      return scan_cells(a, b, s, goal_on_line, goal_a, cells);
    const Line here = line<Axis>(b), low = line<Axis>(b - 1), high = line<Axis>(b + 1);
    if (s > 0) {
      for (int p = a + 1;; p += 64) {
        if (p >= here.length) return 0;
        const std::uint64_t c = here.get(p), lo = low.get(p), hi = high.get(p);
        const std::uint64_t forced = (lo & ~low.get(p - 1)) | (hi & ~high.get(p - 1));
        std::uint64_t event = forced;
        if (goal_on_line && goal_a >= p && goal_a < p + 64)
          event |= std::uint64_t{1} << (goal_a - p);
        event &= c;
        const std::uint64_t blocked = ~c;
        cells += 3 * 64;
        if (blocked == 0 && event == 0) continue;
        const int first_event = event ? std::countr_zero(event) : 64;
        const int first_block = blocked ? std::countr_zero(blocked) : 64;
        return first_event < first_block ? p + first_event - a : 0;
      }
    }
    for (int p = a - 1;; p -= 64) {
      if (p < 0) return 0;
      const int q = p - 63;  // the window's lowest position (may be negative: reads 0 there)
      const std::uint64_t c = here.get(q), lo = low.get(q), hi = high.get(q);
      const std::uint64_t forced = (lo & ~low.get(q + 1)) | (hi & ~high.get(q + 1));
      std::uint64_t event = forced;
      if (goal_on_line && goal_a <= p && goal_a > p - 64) event |= std::uint64_t{1} << (goal_a - q);
      event &= c;
      const std::uint64_t blocked = ~c;
      cells += 3 * 64;
      if (blocked == 0 && event == 0) continue;
      const int last_event = event ? 63 - std::countl_zero(event) : -1;
      const int last_block = blocked ? 63 - std::countl_zero(blocked) : -1;
      return last_event > last_block ? a - (q + last_event) : 0;
    }
  }

 private:
  // One line of cells (a row, or a sealed grid's column) as bits; positions outside [0, length)
  // and lines outside the grid read as blocked.
  struct Line {
    const std::uint64_t* words = nullptr;
    std::uint64_t count = 0;  // words of the whole array (reads stay inside it)
    std::uint64_t start = 0;  // bit index of position 0
    int length = 0;
    // Bits of positions p .. p + 63 (bit i: position p + i).
    [[gnu::always_inline]] std::uint64_t get(int p) const {
      if (words == nullptr || p >= length || p <= -64) return 0;
      std::uint64_t v;
      if (p < 0) {
        v = read(start) << (-p);
      } else {
        v = read(start + static_cast<std::uint64_t>(p));
      }
      const int left = length - p;  // positions p .. length - 1 are in the line
      return left >= 64 ? v : v & ((std::uint64_t{1} << left) - 1);
    }
    [[gnu::always_inline]] std::uint64_t read(std::uint64_t bit) const {
      const std::uint64_t w = bit >> 6;
      const int shift = static_cast<int>(bit & 63);
      std::uint64_t v = words[w] >> shift;
      if (shift != 0 && w + 1 < count) v |= words[w + 1] << (64 - shift);
      return v;
    }
  };
  template <int Axis>
  [[gnu::always_inline]] Line line(int b) const {
    Line l;
    if (Axis == 0) {
      if (static_cast<unsigned>(b) >= height_) return l;
      l.words = words_;
      l.count = word_count_;
      l.start = static_cast<std::uint64_t>(b) * row_bits_;
      l.length = static_cast<int>(width_);
    } else {
      if (static_cast<unsigned>(b) >= width_) return l;
      l.words = grid_.transposed().data();
      l.count = grid_.transposed().size();
      l.start = static_cast<std::uint64_t>(b) * grid_.column_bits();
      l.length = static_cast<int>(height_);
    }
    return l;
  }
  // Along y on an unsealed grid: the cell-by-cell run.
  int scan_cells(int a, int b, int s, bool goal_on_line, int goal_a, std::uint64_t& cells) const {
    bool low_before = free(b - 1, a), high_before = free(b + 1, a);
    for (int n = 1;; ++n) {
      a += s;
      cells += 3;
      if (!free(b, a)) return 0;
      if (goal_on_line && a == goal_a) return n;
      const bool low = free(b - 1, a), high = free(b + 1, a);
      if ((low && !low_before) || (high && !high_before)) return n;
      low_before = low;
      high_before = high;
    }
  }

  const OccupancyGrid& grid_;
  const std::uint64_t* words_;
  std::uint64_t word_count_;
  std::uint64_t row_bits_;
  unsigned width_, height_;
  int extent_;
};

template <class Cells>
class JumpPointGraph {
 public:
  using State = PackedKey<1>;
  using Move = std::uint16_t;  // (run length << 3) | direction
  using Hash = PackedKeyHash<1>;
  using Cost = LatticeCost;
  static constexpr Move kNoMove = 0xFFFF;
  // Run lengths must fit 13 bits and never spell kNoMove.
  static constexpr int kMaxExtent = 8191;

  JumpPointGraph(const Cells& cells, std::array<int, 2> goal)
      : cells_(cells),
        layout_(2, cells.extent()),
        extent_(cells.extent()),
        goal_x_(goal[0]),
        goal_y_(goal[1]) {
    if (extent_ > kMaxExtent) throw std::logic_error("JumpPointGraph: extent too large");
  }

  const KeyLayout& layout() const { return layout_; }
  std::uint64_t collision_checks() const { return checks_; }

  State pack(int x, int y) const {
    return State{
        {static_cast<std::uint64_t>(x) | (static_cast<std::uint64_t>(y) << layout_.shift_of(1))}};
  }
  State pack(std::span<const int> c) const { return pack(c[0], c[1]); }
  std::array<int, 2> unpack(const State& s) const {
    return {static_cast<int>(s.w[0] & layout_.mask()),
            static_cast<int>(s.w[0] >> layout_.shift_of(1))};
  }

  // Expansion of the start (no arriving move): every direction.
  template <class Emit>
  void for_each_successor(const State& s, Emit&& emit) const {
    for_each_successor_after(s, kNoMove, emit);
  }

  template <class Emit>
  void for_each_successor_after(const State& s, Move arrived, Emit&& emit) const {
    // Plain ints, not a structured binding: the lambda below captures them, which clang
    // before 16 refuses for bindings (the ThreadSanitizer stage builds with clang 14).
    const std::array<int, 2> xy = unpack(s);
    const int x = xy[0], y = xy[1];
    std::uint64_t checks = 0;
    auto run = [&](int dir) __attribute__((always_inline)) {
      const int dx = kDx[dir], dy = kDy[dir];
      const int n = dir < 2   ? jump_straight<0>(x, y, dx, checks)
                    : dir < 4 ? jump_straight<1>(y, x, dy, checks)
                              : jump_diagonal(x, y, dx, dy, checks);
      if (n == 0) return;
      emit(pack(x + n * dx, y + n * dy), dir < 4 ? LatticeCost{n, 0, 0} : LatticeCost{0, n, 0},
           static_cast<Move>((n << 3) | dir));
    };
    if (arrived == kNoMove) {
      for (int dir = 0; dir < 8; ++dir) run(dir);
    } else {
      const int dir = arrived & 7;
      const int dx = kDx[dir], dy = kDy[dir];
      if (dir >= 4) {
        run(direction(dx, 0));
        run(direction(0, dy));
        run(dir);
      } else {
        run(dir);
        // Forced sides: the side cell here free, the one beside the previous cell blocked.
        for (int side = -1; side <= 1; side += 2) {
          const int sx = dx == 0 ? x + side : x, sy = dx == 0 ? y : y + side;
          if (sx < 0 || sx >= extent_ || sy < 0 || sy >= extent_) continue;
          checks += 2;
          if (cells_.free(sx, sy) && !cells_.free(sx - dx, sy - dy)) {
            const int tx = dx == 0 ? side : 0, ty = dx == 0 ? 0 : side;
            run(direction(tx, ty));
            run(direction(dx + tx, dy + ty));
          }
        }
      }
    }
    checks_ += checks;
  }

  State predecessor(const State& t, Move m) const {
    const auto [x, y] = unpack(t);
    const int dir = m & 7, n = m >> 3;
    return pack(x - n * kDx[dir], y - n * kDy[dir]);
  }

  // The run a->b re-walked cell by cell with the cells' independent test and the seed rule.
  // Returns its length, or -1 if it is not a straight or diagonal run of legal moves.
  double checked_edge_length(const State& a, const State& b) const {
    const auto [ax, ay] = unpack(a);
    const auto [bx, by] = unpack(b);
    const int ddx = bx - ax, ddy = by - ay;
    const int n = std::max(std::abs(ddx), std::abs(ddy));
    if (n == 0 || (ddx != 0 && ddy != 0 && std::abs(ddx) != std::abs(ddy))) return -1.0;
    const int sx = (ddx > 0) - (ddx < 0), sy = (ddy > 0) - (ddy < 0);
    auto inside = [&](int x, int y) { return x >= 0 && x < extent_ && y >= 0 && y < extent_; };
    int x = ax, y = ay;
    if (!inside(x, y) || !cells_.checked_free(x, y)) return -1.0;
    for (int i = 0; i < n; ++i) {
      const int nx = x + sx, ny = y + sy;
      if (!inside(nx, ny) || !cells_.checked_free(nx, ny)) return -1.0;
      if (sx != 0 && sy != 0 && (!cells_.checked_free(nx, y) || !cells_.checked_free(x, ny)))
        return -1.0;
      x = nx;
      y = ny;
    }
    return sx != 0 && sy != 0 ? n * 1.41421356237309504880 : n;
  }

  // A path of jump points as unit lattice moves (every cell of every run).
  std::vector<State> unit_steps(const std::vector<State>& jumps) const {
    std::vector<State> steps;
    if (jumps.empty()) return steps;
    steps.push_back(jumps.front());
    for (std::size_t i = 1; i < jumps.size(); ++i) {
      auto [x, y] = unpack(jumps[i - 1]);
      const auto [bx, by] = unpack(jumps[i]);
      const int sx = (bx > x) - (bx < x), sy = (by > y) - (by < y);
      while (x != bx || y != by) {
        x += sx;
        y += sy;
        steps.push_back(pack(x, y));
      }
    }
    return steps;
  }

 private:
  // Directions 0-3 straight, 4-7 diagonal.
  static constexpr std::array<int, 8> kDx = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr std::array<int, 8> kDy = {0, 0, 1, -1, 1, -1, 1, -1};
  static constexpr int direction(int dx, int dy) {
    if (dy == 0) return dx > 0 ? 0 : 1;
    if (dx == 0) return dy > 0 ? 2 : 3;
    return 4 + (dx < 0 ? 2 : 0) + (dy < 0 ? 1 : 0);
  }

  // Cell (a, b) with a along Axis and b across it.
  template <int Axis>
  [[gnu::always_inline]] bool free_along(int a, int b) const {
    return Axis == 0 ? cells_.free(a, b) : cells_.free(b, a);
  }

  // Steps from (a, b) along Axis by s until the goal or a cell with a forced side; returns the
  // number of steps, or 0 if an obstacle or the box's edge comes first.
  template <int Axis>
  [[gnu::always_inline]] int jump_straight(int a, int b, int s, std::uint64_t& checks) const {
    const int goal_a = Axis == 0 ? goal_x_ : goal_y_, goal_b = Axis == 0 ? goal_y_ : goal_x_;
    // Cells that can scan a line a word at a time do (OccupancyCells2D).
    if constexpr (requires { cells_.template scan<Axis>(a, b, s, true, goal_a, checks); })
      return cells_.template scan<Axis>(a, b, s, b == goal_b, goal_a, checks);
    const bool low_side = b > 0, high_side = b + 1 < extent_;
    // Whether the side cells beside the previous cell are free.
    bool low_before = low_side && free_along<Axis>(a, b - 1);
    bool high_before = high_side && free_along<Axis>(a, b + 1);
    checks += 2;
    for (int n = 1;; ++n) {
      a += s;
      if (a < 0 || a >= extent_) return 0;
      ++checks;
      if (!free_along<Axis>(a, b)) return 0;
      if (a == goal_a && b == goal_b) return n;
      checks += 2;
      const bool low = low_side && free_along<Axis>(a, b - 1);
      const bool high = high_side && free_along<Axis>(a, b + 1);
      if ((low && !low_before) || (high && !high_before)) return n;
      low_before = low;
      high_before = high;
    }
  }

  // Diagonal steps from (x, y) until the goal or a cell whose straight runs (along dx, along dy)
  // stop somewhere; 0 if a step is illegal first.
  int jump_diagonal(int x, int y, int dx, int dy, std::uint64_t& checks) const {
    for (int n = 1;; ++n) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || nx >= extent_ || ny < 0 || ny >= extent_) return 0;
      checks += 3;
      if (!cells_.free(nx, y) || !cells_.free(x, ny) || !cells_.free(nx, ny)) return 0;
      x = nx;
      y = ny;
      if (x == goal_x_ && y == goal_y_) return n;
      if (jump_straight<0>(x, y, dx, checks) != 0 || jump_straight<1>(y, x, dy, checks) != 0)
        return n;
    }
  }

  const Cells& cells_;
  KeyLayout layout_;
  int extent_;
  int goal_x_, goal_y_;
  mutable std::uint64_t checks_ = 0;
};

}  // namespace hpcplan
