// The grid engines where the other tests do not reach: the dense engine from 9D to 16D (its
// move-table kernel, used for the seed rule beyond 8D) on tiny lattices, against the sparse
// engine; and the sparse engine's widest keys (four 64-bit words: 16 bits an axis, four axes a
// word, from 13 axes on) against Dijkstra. Every path is walked again move by move by the
// independent oracle of lattice_oracle.hpp. The same problems on 2 ranks are in
// tests/mpi/test_distributed.cpp (DenseHighDims, WidestKeys).
//
// Both the Release and the ASan + UBSan trees compile all 16 dimensions and run these; the
// ThreadSanitizer tree compiles 4 and does not build this file.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "lattice_oracle.hpp"

namespace {

using namespace hpcplan;

// Extents tiny enough that the sparse engine explores the whole lattice in well under a second
// (3^9 = 19,683 states at 9D, 2^16 = 65,536 at 16D, each with up to 2d + 4 C(d, 2) moves).
int tiny_extent(int d) {
  return d == 9 ? 3 : 2;
}

GridReport solve(const GridProblem& p, GridAlgorithm a, GridEngine e, int threads = 1) {
  GridSearchOptions o;
  o.algorithm = a;
  o.engine = e;
  o.keep_path = true;
  o.threads = threads;
  return solve_grid(p, o);
}

// The path joins start to goal by legal moves of free states whose lengths add up to the cost.
void expect_valid_path(const GridProblem& p, const GridReport& r, const std::string& what) {
  const GogField field(p.dims, p.extent, p.gog);
  const oracle::Lattice o(field, p.connectivity == Connectivity::full);
  ASSERT_FALSE(r.result.path.empty()) << what;
  EXPECT_EQ(r.result.path.front(), r.problem.start) << what;
  EXPECT_EQ(r.result.path.back(), r.problem.goal) << what;
  EXPECT_EQ(r.result.path.size(), r.result.hops + 1) << what;
  for (const auto& s : r.result.path) EXPECT_TRUE(o.free(s)) << what;
  std::size_t illegal = 0;
  const double length = o.path_length(r.result.path, &illegal);
  ASSERT_GE(length, 0) << what << ": illegal move at step " << illegal;
  EXPECT_NEAR(length, r.result.cost, 1e-9 * (1 + length)) << what;
}

TEST(DenseHighDims, NineToSixteenDimensionsAgreeWithTheSparseEngine) {
  ASSERT_GE(dense::compiled_dims(), 16)
      << "this build compiles the dense engine for fewer dimensions (HPCPLAN_DENSE_DIMS)";
  SplitMix64 rng(9016);
  int solved = 0, unreachable = 0;
  for (int d = 9; d <= 16; ++d)
    // From 13D on, one open instance: a 16D Dijkstra sweeps its whole lattice in half a second
    // on the dense engine (its move table has 512 moves a state).
    for (int instance = d <= 12 ? 0 : 1; instance < 3; ++instance) {
      GridProblem p;
      p.dims = d;
      p.extent = tiny_extent(d);
      p.gog.seed = rng.next();
      // Runs of one cell (b_v = b_p = 0): with GOG's default runs of 8 a lattice this small
      // has no blocked state at all. The third instance dense enough that start and goal are
      // often cut apart.
      p.gog.shift_v = 0;
      p.gog.shift_p = 0;
      p.gog.density = instance == 2 ? 0.9 : 0.3 + 0.3 * rng.next_unit();
      // Start and goal drawn among the free states (the default corners may be blocked).
      const GogField field(p.dims, p.extent, p.gog);
      auto draw_free = [&] {
        std::vector<int> s(static_cast<std::size_t>(d));
        do {
          for (int& c : s) c = static_cast<int>(rng.next_below(static_cast<std::uint64_t>(p.extent)));
        } while (!field.is_free(s));
        return s;
      };
      p.start = draw_free();
      p.goal = draw_free();
      for (const GridAlgorithm a : {GridAlgorithm::bfs, GridAlgorithm::dijkstra}) {
        const std::string what = std::to_string(d) + "D extent " + std::to_string(p.extent) +
                                 " seed " + std::to_string(p.gog.seed) + " " +
                                 std::string(to_string(a));
        const GridReport sparse = solve(p, a, GridEngine::sparse);
        const GridReport dense = solve(p, a, GridEngine::dense);
        ASSERT_EQ(dense.options.engine, "dense") << what;
        ASSERT_EQ(sparse.options.engine, "sparse") << what;
        ASSERT_EQ(dense.result.status, sparse.result.status) << what;
        if (sparse.result.status != Status::solved) {
          EXPECT_EQ(sparse.result.status, Status::no_path) << what;
          ++unreachable;
          continue;
        }
        ++solved;
        EXPECT_GT(field.blocked_fraction(), 0.05) << what;
        // Fewest moves for BFS (paths of equal length may differ in cost), least cost for
        // Dijkstra (and so its moves: a cost a + b sqrt 2 has one a and one b).
        EXPECT_EQ(dense.result.hops, sparse.result.hops) << what;
        if (a == GridAlgorithm::dijkstra) {
          EXPECT_NEAR(dense.result.cost, sparse.result.cost, 1e-9 * (1 + sparse.result.cost))
              << what;
        }
        expect_valid_path(p, dense, what + " (dense)");
        expect_valid_path(p, sparse, what + " (sparse)");
        // Two threads split the slab; the answer and the count of settled states stay.
        const GridReport two = solve(p, a, GridEngine::dense, 2);
        EXPECT_EQ(two.result.cost, dense.result.cost) << what;
        EXPECT_EQ(two.result.path, dense.result.path) << what;
        EXPECT_EQ(two.result.counters.expanded, dense.result.counters.expanded) << what;
      }
    }
  // Both outcomes occur, so neither branch above is vacuous.
  EXPECT_GE(solved, 12);
  EXPECT_GE(unreachable, 2);
}

// Four-word keys: 13 to 16 axes of extent above 4,096 (13 bits an axis, four axes a word).
// The problems sit in a far corner of a huge lattice, goal one or two moves from start: in 16D
// a state has up to 512 moves, so Dijkstra (the oracle here: no heuristic) can only settle a
// ball of radius about 2. A* and weighted A* must match it (wA* within its bound), BFS its fewest moves.
TEST(WidestKeys, FourWordKeysAgreeWithDijkstra) {
  SplitMix64 rng(4444);
  int solved = 0;
  for (const int d : {13, 16})
    for (int instance = 0; instance < 2; ++instance) {
      GridProblem p;
      p.dims = d;
      p.extent = 5000;
      p.gog.density = 0.3;
      // A free start and a free goal high in the lattice, so that the packed fields use their
      // top bits; fields drawn until both are free.
      for (int tries = 0; tries < 100 && !p.start; ++tries) {
        p.gog.seed = rng.next();
        const GogField field(p.dims, p.extent, p.gog);
        std::vector<int> start(d, p.extent - 7), goal(d, p.extent - 7);
        if (instance == 0) {
          ++goal[0];  // a diagonal across the first and the last word
          ++goal[d - 1];
        } else {
          goal[d - 1] += 2;  // two steps along the last word's top field
        }
        if (field.is_free(start) && field.is_free(goal)) {
          p.start = start;
          p.goal = goal;
        }
      }
      ASSERT_TRUE(p.start.has_value()) << d << "D: no free start and goal in 100 fields";
      const std::string what = std::to_string(d) + "D seed " + std::to_string(p.gog.seed);
      const GridReport dij = solve(p, GridAlgorithm::dijkstra, GridEngine::sparse);
      ASSERT_EQ(dij.options.key_words, 4) << what;
      ASSERT_EQ(dij.result.status, Status::solved) << what;
      expect_valid_path(p, dij, what + " dijkstra");
      const GridReport astar = solve(p, GridAlgorithm::astar, GridEngine::sparse);
      ASSERT_EQ(astar.result.status, Status::solved) << what;
      EXPECT_NEAR(astar.result.cost, dij.result.cost, 1e-9 * dij.result.cost) << what;
      expect_valid_path(p, astar, what + " astar");
      GridSearchOptions wo;
      wo.algorithm = GridAlgorithm::wastar;
      wo.weight = 2.0;
      wo.keep_path = true;
      const GridReport wastar = solve_grid(p, wo);
      ASSERT_EQ(wastar.result.status, Status::solved) << what;
      EXPECT_LE(wastar.result.cost, 2.0 * dij.result.cost + 1e-9) << what;
      expect_valid_path(p, wastar, what + " wastar");
      const GridReport bfs = solve(p, GridAlgorithm::bfs, GridEngine::sparse);
      ASSERT_EQ(bfs.result.status, Status::solved) << what;
      EXPECT_LE(bfs.result.hops, dij.result.hops) << what;
      expect_valid_path(p, bfs, what + " bfs");
      ++solved;
    }
  EXPECT_EQ(solved, 4);
}

}  // namespace
