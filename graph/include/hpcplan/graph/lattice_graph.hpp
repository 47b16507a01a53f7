#pragma once
// The implicit lattice graph over an obstacle source (the GOG field, or an occupancy grid a
// user brings): vertices are generated on the fly, never stored.
//
// Seed rule (seed 002 Algorithm 2): +-1 along one axis (cost 1), or along two distinct axes
// (cost sqrt2) when both one-axis intermediate states are free. The one-axis neighbours are
// the same states as those intermediates, so each is evaluated once per expansion.
// Full rule (d <= 4): +-1 along any non-empty set of k axes (cost sqrt k) when every state of
// the unit sub-cube spanned by the move is free (no corner cutting); for k = 2 this is the
// seed rule.
//
// Validity during expansion is O(1) per neighbour either way: on GOG incremental (a neighbour's
// level sum differs from the expanded state's in one or two axis terms), on an occupancy grid
// one bit at the expanded state's bit index plus the move's stride. Each such evaluation of a
// state's validity counts as one collision check. The source's kind is decided once per
// expansion, outside the loops over moves.
//
// Threads: a graph belongs to one run (its check counter is a plain member); the field it
// reads may be shared.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hpcplan/env/obstacle_source.hpp"
#include "hpcplan/graph/lattice_cost.hpp"
#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan {

enum class Connectivity { seed_pairs, full };

inline constexpr int kMaxFullConnectivityDims = 4;

template <int W>
class LatticeGraph {
 public:
  using State = PackedKey<W>;
  using Move = std::uint16_t;
  using Hash = PackedKeyHash<W>;
  using Cost = LatticeCost;
  static constexpr Move kNoMove = 0xFFFF;
  // Every move changes each coordinate by at most this much (both rules): an owner whose
  // region holds x's whole unit neighbourhood owns all of x's successors.
  static constexpr int kMoveRadius = 1;

  LatticeGraph(const ObstacleSource& field, Connectivity connectivity)
      : field_(field),
        layout_(field.dims(), field.extent()),
        connectivity_(connectivity),
        dims_(field.dims()),
        extent_(field.extent()) {
    if (layout_.words() > W) throw std::logic_error("LatticeGraph: key width too small");
    if (connectivity == Connectivity::full && dims_ > kMaxFullConnectivityDims)
      throw std::logic_error("full connectivity is limited to d <= 4");
    if (field.is_gog()) {
      threshold_ = field.gog().threshold();
      for (int a = 0; a < dims_; ++a) tables_[a] = field.gog().level_table(a);
    } else {
      grid_ = &field.occupancy();
    }
    for (int a = 0; a < dims_; ++a) {
      size_[a] = field.size(a);
      bit_stride_[a] = grid_ ? grid_->stride(a) : 0;
    }
    if (connectivity == Connectivity::seed_pairs)
      build_seed_moves();
    else
      build_full_moves();
  }

  const KeyLayout& layout() const { return layout_; }
  const ObstacleSource& field() const { return field_; }
  Connectivity connectivity() const { return connectivity_; }
  std::uint64_t collision_checks() const { return checks_; }
  std::size_t max_successors() const { return moves_.size(); }

  State pack(std::span<const int> coords) const { return layout_.pack<W>(coords); }
  std::vector<int> unpack(const State& s) const {
    std::vector<int> c(dims_);
    layout_.unpack(s, c.data());
    return c;
  }
  bool is_free(const State& s) const {
    int c[kMaxDims];
    layout_.unpack(s, c);
    return field_.is_free(std::span<const int>(c, dims_));
  }

  State predecessor(const State& t, Move m) const {
    State p = t;
    for (int w = 0; w < W; ++w) p.w[w] -= moves_[m].delta[w];
    return p;
  }

  // Calls emit(successor, edge_cost, move) for every legal move out of x.
  template <class Emit>
  void for_each_successor(const State& x, Emit&& emit) const {
    if (connectivity_ == Connectivity::seed_pairs)
      expand_seed_rule(x, emit);
    else
      expand_full(x, emit);
  }

  // Independent re-validation for returned paths: recomputes everything from the GOG formula
  // or the occupancy grid's cell test (not the level tables, incremental sums or bit strides).
  // Returns the move's length, or -1 if a->b is not a legal move between free states.
  double checked_edge_length(const State& a, const State& b) const {
    int ca[kMaxDims], cb[kMaxDims];
    layout_.unpack(a, ca);
    layout_.unpack(b, cb);
    int axes[kMaxDims], steps[kMaxDims], k = 0;
    for (int i = 0; i < dims_; ++i) {
      const int diff = cb[i] - ca[i];
      if (diff < -1 || diff > 1) return -1.0;
      if (diff != 0) {
        axes[k] = i;
        steps[k] = diff;
        ++k;
      }
    }
    if (k == 0) return -1.0;
    if (connectivity_ == Connectivity::seed_pairs && k > 2) return -1.0;
    // Every corner of the spanned sub-cube (including a and b) must be free.
    for (unsigned subset = 0; subset < (1u << k); ++subset) {
      int corner[kMaxDims];
      std::copy(ca, ca + dims_, corner);
      for (int j = 0; j < k; ++j)
        if (subset & (1u << j)) corner[axes[j]] += steps[j];
      if (!field_.is_free(std::span<const int>(corner, dims_))) return -1.0;
    }
    return std::sqrt(static_cast<double>(k));
  }

 private:
  struct MoveDef {
    std::array<std::uint64_t, W> delta{};
    LatticeCost cost = LatticeCost::for_axes(1);
    std::vector<int> corners;  // full rule: neighbourhood indices that must be free
  };

  void build_seed_moves() {
    // Order must match expand_seed_rule: singles (axis, -/+), then pairs i<k (-/+, -/+).
    for (int i = 0; i < dims_; ++i)
      for (int s = -1; s <= 1; s += 2) {
        MoveDef m;
        layout_.add_step<W>(m.delta, i, s);
        moves_.push_back(m);
      }
    for (int i = 0; i < dims_; ++i)
      for (int k = i + 1; k < dims_; ++k)
        for (int si = -1; si <= 1; si += 2)
          for (int sk = -1; sk <= 1; sk += 2) {
            MoveDef m;
            m.cost = LatticeCost::for_axes(2);
            layout_.add_step<W>(m.delta, i, si);
            layout_.add_step<W>(m.delta, k, sk);
            moves_.push_back(m);
          }
  }

  // Neighbourhood cells are indexed in base 3 (digit 0,1,2 = step -1,0,+1 per axis).
  void build_full_moves() {
    int cells = 1;
    for (int i = 0; i < dims_; ++i) cells *= 3;
    const int centre = (cells - 1) / 2;
    for (int cell = 0; cell < cells; ++cell) {
      if (cell == centre) continue;
      MoveDef m;
      int digits[kMaxDims], k = 0;
      for (int i = 0, c = cell; i < dims_; ++i, c /= 3) {
        digits[i] = c % 3;
        if (digits[i] != 1) {
          layout_.add_step<W>(m.delta, i, digits[i] - 1);
          ++k;
        }
      }
      m.cost = LatticeCost::for_axes(k);
      // Corners: every cell whose digits are, per axis, either 1 or the move's digit.
      for (int other = 0; other < cells; ++other) {
        bool inside = other != centre;
        for (int i = 0, c = other; i < dims_ && inside; ++i, c /= 3)
          inside = (c % 3 == 1) || (c % 3 == digits[i]);
        if (inside) m.corners.push_back(other);
      }
      moves_.push_back(std::move(m));
    }
    full_cells_ = cells;
  }

  State step(const State& x, Move m) const {
    State t = x;
    for (int w = 0; w < W; ++w) t.w[w] += moves_[m].delta[w];
    return t;
  }

  // Decodes x into c and returns its GOG level sum, the base of every incremental check.
  int unpack_with_level_sum(const State& x, int* c) const {
    layout_.unpack(x, c);
    int sum = 0;
    for (int a = 0; a < dims_; ++a) sum += tables_[a][c[a]];
    return sum;
  }

  // The seed rule on either source. The one-axis neighbours are evaluated first (GOG: level
  // sums, incrementally; occupancy: one bit each at the expanded state's bit index plus the
  // axis's stride), then every move is emitted by one loop, so the code that stores a
  // successor (inlined from the search) exists once per instantiation, not once per source.
  template <class Emit>
  void expand_seed_rule(const State& x, Emit& emit) const {
    int c[kMaxDims];
    layout_.unpack(x, c);
    // base: the expanded state's level sum or bit index; change[a][s]: what a step along axis
    // a (s = 0: -1, 1: +1) adds to it; free1: that one-axis neighbour is in the box and free.
    std::int64_t base, change[kMaxDims][2];
    bool free1[kMaxDims][2];
    std::uint64_t checks = grid_ ? seed_singles_bits(c, base, change, free1)
                                 : seed_singles_gog(c, base, change, free1);
    Move id = 0;
    constexpr LatticeCost kOne = LatticeCost::for_axes(1), kTwo = LatticeCost::for_axes(2);
    for (int a = 0; a < dims_; ++a)
      for (int s = 0; s < 2; ++s, ++id)
        if (free1[a][s]) emit(step(x, id), kOne, id);
    for (int i = 0; i < dims_; ++i)
      for (int k = i + 1; k < dims_; ++k)
        for (int si = 0; si < 2; ++si)
          for (int sk = 0; sk < 2; ++sk, ++id) {
            if (!free1[i][si] || !free1[k][sk]) continue;
            ++checks;
            if (free_at(base + change[i][si] + change[k][sk])) emit(step(x, id), kTwo, id);
          }
    checks_ += checks;
  }

  // Whether the state at a level sum (GOG) or bit index (occupancy) is free.
  [[gnu::always_inline]] bool free_at(std::int64_t v) const {
    return grid_ ? grid_->free_at(static_cast<std::uint64_t>(v)) : v < threshold_;
  }
  std::uint64_t seed_singles_gog(const int* c, std::int64_t& base,
                                 std::int64_t (&change)[kMaxDims][2],
                                 bool (&free1)[kMaxDims][2]) const {
    int sum = 0;
    for (int a = 0; a < dims_; ++a) sum += tables_[a][c[a]];
    base = sum;
    std::uint64_t checks = 0;
    for (int a = 0; a < dims_; ++a) {
      const int here = tables_[a][c[a]];
      for (int s = 0; s < 2; ++s) {
        const int nc = c[a] + (s ? 1 : -1);
        free1[a][s] = false;
        if (nc < 0 || nc >= extent_) continue;
        ++checks;
        change[a][s] = tables_[a][nc] - here;
        free1[a][s] = sum + change[a][s] < threshold_;
      }
    }
    return checks;
  }
  std::uint64_t seed_singles_bits(const int* c, std::int64_t& base,
                                  std::int64_t (&change)[kMaxDims][2],
                                  bool (&free1)[kMaxDims][2]) const {
    base = static_cast<std::int64_t>(grid_->index(c));
    std::uint64_t checks = 0;
    for (int a = 0; a < dims_; ++a)
      for (int s = 0; s < 2; ++s) {
        const int nc = c[a] + (s ? 1 : -1);
        free1[a][s] = false;
        if (nc < 0 || nc >= size_[a]) continue;
        ++checks;
        change[a][s] = s ? bit_stride_[a] : -bit_stride_[a];
        free1[a][s] = grid_->free_at(static_cast<std::uint64_t>(base + change[a][s]));
      }
    return checks;
  }

  template <class Emit>
  void expand_full(const State& x, Emit& emit) const {
    int c[kMaxDims];
    const int sum = grid_ ? 0 : unpack_with_level_sum(x, c);
    if (grid_) layout_.unpack(x, c);
    const std::int64_t here = grid_ ? static_cast<std::int64_t>(grid_->index(c)) : 0;
    bool free_cell[81];  // 3^4
    std::uint64_t checks = 0;
    const int centre = (full_cells_ - 1) / 2;
    for (int cell = 0; cell < full_cells_; ++cell) {
      if (cell == centre) {
        free_cell[cell] = true;
        continue;
      }
      int s = sum;
      std::int64_t bit = here;
      bool inside = true;
      for (int i = 0, q = cell; i < dims_; ++i, q /= 3) {
        const int step = q % 3 - 1;
        if (step == 0) continue;
        const int nc = c[i] + step;
        if (nc < 0 || nc >= size_[i]) {
          inside = false;
          break;
        }
        if (grid_)
          bit += step * bit_stride_[i];
        else
          s += tables_[i][nc] - tables_[i][c[i]];
      }
      if (inside) ++checks;
      free_cell[cell] =
          inside && (grid_ ? grid_->free_at(static_cast<std::uint64_t>(bit)) : s < threshold_);
    }
    for (Move id = 0; id < moves_.size(); ++id) {
      bool ok = true;
      for (int corner : moves_[id].corners) ok = ok && free_cell[corner];
      if (ok) emit(step(x, id), moves_[id].cost, id);
    }
    checks_ += checks;
  }

  ObstacleSource field_;
  KeyLayout layout_;
  Connectivity connectivity_;
  int dims_;
  int extent_;
  // GOG: the threshold and per-axis level tables. Occupancy: the grid, its bit strides.
  int threshold_ = 0;
  std::array<const std::uint8_t*, kMaxDims> tables_{};
  const OccupancyGrid* grid_ = nullptr;
  std::array<int, kMaxDims> size_{};  // sides per axis (extent on GOG)
  std::array<std::int64_t, kMaxDims> bit_stride_{};
  std::vector<MoveDef> moves_;
  int full_cells_ = 0;
  mutable std::uint64_t checks_ = 0;
};

}  // namespace hpcplan
