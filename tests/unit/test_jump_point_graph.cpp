// Jump point search against a textbook Dijkstra on every cell, on arbitrary obstacle maps (not
// only the GOG fields' separable ones, whose blocked cells line up in rows and columns), and
// on the planner's GOG problems.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/graph/jump_point_graph.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/stamped_dense_map.hpp"
#include "lattice_oracle.hpp"
#include "support/bitmap_dijkstra.hpp"

namespace {

using namespace hpcplan;

// A square map of independently drawn cells.
struct BitmapCells {
  int size = 0;
  std::vector<char> blocked;
  int extent() const { return size; }
  bool free(int x, int y) const { return !blocked[static_cast<std::size_t>(y) * size + x]; }
  bool checked_free(int x, int y) const { return free(x, y); }
};

double reference_cost(const BitmapCells& m, int sx, int sy, int gx, int gy) {
  return test_support::bitmap_dijkstra(
             m.size, [&m](int x, int y) { return !m.free(x, y); }, sx, sy, gx, gy)
      .cost;
}

// Octile distance as the exact lattice cost: the heuristic the planner gives A* at 2D.
struct Octile {
  static constexpr bool kConsistent = true;
  const JumpPointGraph<BitmapCells>* graph;
  int gx, gy;
  LatticeCost operator()(const PackedKey<1>& s) const {
    const auto [x, y] = graph->unpack(s);
    const int ax = std::abs(x - gx), ay = std::abs(y - gy);
    return {std::max(ax, ay) - std::min(ax, ay), std::min(ax, ay), 0};
  }
};

TEST(JumpPointGraph, MatchesDijkstraOnRandomMaps) {
  SplitMix64 rng(20261126);
  int solved = 0, unreachable = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    BitmapCells m;
    m.size = 2 + static_cast<int>(rng.next_below(30));
    const double density = 0.05 + 0.5 * rng.next_unit();
    m.blocked.resize(static_cast<std::size_t>(m.size) * m.size);
    for (auto& b : m.blocked) b = rng.next_unit() < density;
    auto draw_free = [&](int& x, int& y) {
      do {
        x = static_cast<int>(rng.next_below(m.size));
        y = static_cast<int>(rng.next_below(m.size));
      } while (!m.free(x, y));
    };
    int sx, sy, gx, gy;
    m.blocked[0] = 0;  // at least one free cell
    draw_free(sx, sy);
    draw_free(gx, gy);
    const JumpPointGraph<BitmapCells> graph(m, {gx, gy});
    const Octile h{&graph, gx, gy};
    search::Options o;
    o.dense_keys = graph.layout().dense_index_bound();
    const auto r = search::best_first_search<search::StampedDensePolicy>(graph, graph.pack(sx, sy),
                                                                         graph.pack(gx, gy), h, o);
    const double want = reference_cost(m, sx, sy, gx, gy);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " size " << m.size << " start " << sx
                                      << "," << sy << " goal " << gx << "," << gy);
    if (std::isinf(want)) {
      EXPECT_EQ(r.status, search::Status::no_path);
      ++unreachable;
      continue;
    }
    ASSERT_EQ(r.status, search::Status::solved);
    EXPECT_NEAR(r.cost, want, 1e-9);
    // The runs expanded into unit moves re-derive the same length move by move.
    const auto steps = graph.unit_steps(r.path);
    double length = 0.0;
    for (std::size_t i = 1; i < steps.size(); ++i) {
      const double len = graph.checked_edge_length(steps[i - 1], steps[i]);
      ASSERT_GT(len, 0.0) << "step " << i;
      ASSERT_LE(len, 1.5) << "step " << i << " is not a unit move";
      length += len;
    }
    EXPECT_NEAR(length, want, 1e-9);
    ++solved;
  }
  // Both answers were exercised in quantity.
  EXPECT_GT(solved, 1500);
  EXPECT_GT(unreachable, 100);
}

TEST(JumpPointGraph, RefusesRunsThatAreNotLegal) {
  BitmapCells m;
  m.size = 5;
  m.blocked.assign(25, 0);
  m.blocked[1 * 5 + 1] = 1;  // (1,1)
  const JumpPointGraph<BitmapCells> graph(m, {4, 4});
  EXPECT_EQ(graph.checked_edge_length(graph.pack(0, 0), graph.pack(3, 0)), 3.0);
  EXPECT_LT(graph.checked_edge_length(graph.pack(0, 0), graph.pack(2, 2)), 0.0);  // through (1,1)
  EXPECT_LT(graph.checked_edge_length(graph.pack(0, 1), graph.pack(2, 1)), 0.0);  // through (1,1)
  EXPECT_LT(graph.checked_edge_length(graph.pack(0, 1), graph.pack(1, 2)), 0.0);  // cuts (1,1)
  EXPECT_LT(graph.checked_edge_length(graph.pack(0, 0), graph.pack(2, 1)), 0.0);  // not a run
  EXPECT_LT(graph.checked_edge_length(graph.pack(0, 0), graph.pack(0, 0)), 0.0);
  EXPECT_NEAR(graph.checked_edge_length(graph.pack(2, 2), graph.pack(4, 4)), 2 * std::sqrt(2.0),
              1e-12);
}

// The planner prunes 2D A* with jump points, returns unit moves, and its cost is the oracle's.
TEST(JumpPointGraph, PlannerUsesItFor2DAStarAndMatchesTheOracle) {
  SplitMix64 rng(77);
  for (int trial = 0; trial < 200; ++trial) {
    GridProblem p;
    p.dims = 2;
    p.extent = 10 + static_cast<int>(rng.next_below(80));
    p.gog.seed = rng.next();
    p.gog.shift_v = static_cast<int>(rng.next_below(3));
    p.gog.shift_p = static_cast<int>(rng.next_below(5));
    p.gog.density = 0.1 + 0.5 * rng.next_unit();
    const GogField field(2, p.extent, p.gog);
    GridSearchOptions o;
    o.keep_path = true;
    o.max_states = 1'000'000;
    GridReport jps;
    try {
      jps = solve_grid(field, p, o);
    } catch (const InputError&) {
      continue;  // the default corners could not be adjusted to free cells
    }
    o.jump_points = false;
    const GridReport plain = solve_grid(field, p, o);
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    EXPECT_EQ(jps.options.pruning, "jump_points");
    EXPECT_EQ(plain.options.pruning, "none");
    const oracle::Answer want =
        oracle::Lattice(field, false).dijkstra(jps.problem.start, jps.problem.goal);
    ASSERT_EQ(jps.result.status == search::Status::solved, want.reachable);
    ASSERT_EQ(plain.result.status, jps.result.status);
    if (!want.reachable) continue;
    EXPECT_NEAR(jps.result.cost, want.cost, 1e-9);
    EXPECT_NEAR(plain.result.cost, want.cost, 1e-9);
    ASSERT_EQ(jps.result.path.size(), jps.result.hops + 1);
    std::size_t illegal = 0;
    const double length = oracle::Lattice(field, false).path_length(jps.result.path, &illegal);
    ASSERT_GE(length, 0.0) << "illegal move at step " << illegal;
    EXPECT_NEAR(length, want.cost, 1e-9);
    EXPECT_LE(jps.result.counters.expanded, plain.result.counters.expanded);
  }
}

TEST(JumpPointGraph, OnlyPlainAStarAt2DIsPruned) {
  GridProblem p;
  p.dims = 2;
  GridSearchOptions o;
  o.max_states = 1'000'000;
  o.algorithm = GridAlgorithm::dijkstra;
  EXPECT_EQ(solve_grid(p, o).options.pruning, "none");
  o.algorithm = GridAlgorithm::wastar;
  EXPECT_EQ(solve_grid(p, o).options.pruning, "none");
  o.algorithm = GridAlgorithm::astar;
  const GridReport pruned = solve_grid(p, o);
  EXPECT_EQ(pruned.options.pruning, "jump_points");
  o.jump_points = false;
  const GridReport plain = solve_grid(p, o);
  // The default 2D problem: the same optimum with a fraction of the expansions.
  EXPECT_DOUBLE_EQ(pruned.result.cost, plain.result.cost);
  EXPECT_LT(pruned.result.counters.expanded * 4, plain.result.counters.expanded);
  p.dims = 3;
  p.extent = 20;
  o.jump_points = true;
  EXPECT_EQ(solve_grid(p, o).options.pruning, "none");
}

}  // namespace
