#pragma once
// The lattice over a configuration space (env/config_space.hpp): the graph the sparse engine
// (A*, weighted A*, Dijkstra, BFS) and the distributed one search when the world is a
// mechanism's space (the kinematic chain, the hypercube, a space a user defines) rather than
// the GOG field or an occupancy grid.
//
// Vertices: `cells` per axis. On a periodic axis (a joint angle) they sit at lower + i * h with
// h = period / cells and the last one's neighbour is the first again; on a bounded axis at
// lower + i * (upper - lower) / (cells - 1), both bounds included (so the hypercube's corners
// are vertices). Moves: +-1 cell along one axis, or (seed_pairs, seed 002's rule) along two
// axes at once. A move is legal when its end is valid and the straight motion to it is, tested
// at the space's resolution (config_space.hpp's Motion: the same samples the path's re-check
// and the OMPL adapter test). Edge costs and the heuristic are Euclidean lengths in the space's
// own coordinates, periodic axes the short way, so the search's cost is the path's length in
// the metric every planner of the comparison reports.
//
// Checks go in batches (VAMP's idea): an expansion first gathers every successor the search
// could still improve and whose end is not already known, tests their ends as one batch, then
// the inner samples of every edge whose end passed as a second batch. Ends are remembered (a
// vertex is reached from up to 2 x moves neighbours), edges are not (each is tested once per
// expansion of its tail, and a consistent heuristic expands a state once).
//
// Threads: a graph belongs to one run (its end cache and counters are plain members); the space
// it reads may be shared.
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <absl/container/flat_hash_map.h>

#include "hpcplan/env/config_space.hpp"
#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan {

enum class CSpaceMoves { axes, seed_pairs };
std::string_view to_string(CSpaceMoves m);
CSpaceMoves parse_cspace_moves(std::string_view name);  // InputError if unknown

class CSpaceGraph {
 public:
  static constexpr int kWords = 2;
  using State = PackedKey<kWords>;
  using Move = std::uint16_t;
  using Hash = PackedKeyHash<kWords>;
  using Cost = double;
  static constexpr Move kNoMove = 0xFFFF;

  // InputError for cells outside 2..65535 (3.. on a periodic axis), more than kMaxDims axes, or
  // a lattice whose keys need more than 128 bits.
  CSpaceGraph(const ConfigSpace& space, int cells, CSpaceMoves moves);

  const ConfigSpace& space() const { return space_; }
  const KeyLayout& layout() const { return layout_; }
  int dims() const { return dims_; }
  int cells() const { return cells_; }
  CSpaceMoves moves() const { return moves_kind_; }
  std::size_t max_successors() const { return moves_.size(); }
  std::uint64_t collision_checks() const { return checks_; }
  std::uint64_t batches() const { return batches_; }
  // false: every state tested one at a time with the space's scalar test (the same answers;
  // the baseline that shows what the batches buy, --checks single).
  void set_batch_checks(bool on) { batch_checks_ = on; }
  bool batch_checks() const { return batch_checks_; }

  State pack(std::span<const int> coords) const { return layout_.pack<kWords>(coords); }
  std::vector<int> unpack(const State& s) const {
    std::vector<int> c(dims_);
    layout_.unpack(s, c.data());
    return c;
  }
  // The configuration of a vertex.
  void vertex(const int* coords, double* q) const {
    for (int a = 0; a < dims_; ++a) q[a] = coordinate(a, coords[a]);
  }
  // One axis's value at cell i: a bounded axis's last cell is its upper bound exactly (not
  // lower + (cells - 1) * step, which round-off can put outside the bounds).
  double coordinate(int axis, int i) const {
    return !periodic_[axis] && i == cells_ - 1 ? upper_[axis] : lower_[axis] + i * step_[axis];
  }
  std::vector<double> vertex(const State& s) const;
  // The vertices around a configuration (each axis's two nearest cells, nearest first), at most
  // `limit`: where an off-lattice start or goal tries to join the lattice.
  std::vector<std::vector<int>> vertices_near(std::span<const double> q, std::size_t limit) const;
  // Euclidean distance in the space's coordinates (periodic axes the short way).
  double distance(std::span<const double> a, std::span<const double> b) const;

  State predecessor(const State& t, Move m) const;

  // Independent re-check for returned paths: a->b must be one legal move; its end and every
  // sample of its motion are tested one state at a time with the space's scalar test (not the
  // batch, not the end cache). Returns the move's length, or -1.
  double checked_edge_length(const State& a, const State& b) const;

  template <class Emit>
  void for_each_successor(const State& x, Emit&& emit) const {
    for_each_successor(x, emit, [](const State&, Cost) { return true; });
  }
  // Calls emit(successor, edge_cost, move) for every legal move out of x that `could_improve`
  // (asked before any check) lets through.
  template <class Emit, class Filter>
  void for_each_successor(const State& x, Emit&& emit, Filter&& could_improve) const {
    int cx[kMaxDims];
    layout_.unpack(x, cx);
    gather_candidates(cx, could_improve);
    check_candidates();
    for (const Candidate& c : candidates_)
      if (c.ok) emit(c.state, moves_[c.move].cost, c.move);
  }

 private:
  struct MoveDef {
    int axis[2] = {0, 0};
    int step[2] = {0, 0};
    int axes = 1;
    double cost = 0.0;
  };
  struct Candidate {
    State state;
    Move move;
    bool ok;
  };

  // The move's end from cx, or false where it leaves a bounded axis.
  bool step(const int* cx, const MoveDef& m, int* out) const;
  template <class Filter>
  void gather_candidates(const int* cx, Filter& could_improve) const {
    candidates_.clear();
    tail_.assign(dims_, 0.0);
    vertex(cx, tail_.data());
    int ct[kMaxDims];
    for (std::size_t m = 0; m < moves_.size(); ++m) {
      if (!step(cx, moves_[m], ct)) continue;
      const State t = pack(std::span<const int>(ct, dims_));
      if (!could_improve(t, moves_[m].cost)) continue;
      candidates_.push_back({t, static_cast<Move>(m), false});
    }
  }
  // Sets each candidate's ok: its end valid (cache, else the first batch) and its motion's inner
  // samples valid (the second batch).
  void check_candidates() const;
  void test(const std::vector<double>& states, std::vector<std::uint8_t>& ok) const;

  const ConfigSpace& space_;
  int dims_;
  int cells_;
  CSpaceMoves moves_kind_;
  KeyLayout layout_;
  std::vector<double> lower_, upper_, step_;
  std::vector<bool> periodic_;
  std::vector<MoveDef> moves_;

  // Per-expansion scratch and the end cache (mutable: the search sees a const graph).
  mutable std::vector<Candidate> candidates_;
  mutable std::vector<double> tail_, batch_;
  mutable std::vector<std::uint8_t> batch_ok_;
  mutable std::vector<std::size_t> pending_;
  mutable absl::flat_hash_map<State, bool, Hash> end_valid_;
  mutable std::uint64_t checks_ = 0;
  mutable std::uint64_t batches_ = 0;
  bool batch_checks_ = true;
};

// The admissible, consistent heuristic of the c-space lattice: the Euclidean distance to the
// goal vertex, periodic axes the short way (no move is shorter than the distance it covers).
// Each axis's squared distance from every cell to the goal's is tabled once: a state's h is
// d table loads and a square root.
class CSpaceHeuristic {
 public:
  CSpaceHeuristic(const CSpaceGraph& graph, const CSpaceGraph::State& goal);
  double operator()(const CSpaceGraph::State& s) const {
    int c[kMaxDims];
    graph_->layout().unpack(s, c);
    double sum = 0.0;
    for (int a = 0; a < dims_; ++a) sum += squared_[static_cast<std::size_t>(a) * cells_ + c[a]];
    return std::sqrt(sum);
  }

 private:
  const CSpaceGraph* graph_;
  int dims_, cells_;
  std::vector<double> squared_;  // [axis * cells + cell]
};

}  // namespace hpcplan
