// The grid engines on configuration spaces (plan/cspace_planner.hpp, graph/cspace_graph.hpp):
// A* against the test's own Dijkstra over the whole lattice (built here from the space's scalar
// test and the motion rule), weighted A* within its bound, BFS's hops, the periodic wrap, a
// space defined in the test (the user's route), the ends joining off-lattice, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <queue>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/benchmark_spaces.hpp"
#include "hpcplan/env/hypercube.hpp"
#include "hpcplan/env/kinematic_chain.hpp"
#include "hpcplan/plan/cspace_planner.hpp"

namespace hpcplan {
namespace {

GridProblem cspace_problem(const BenchmarkSpace& b, int cells, CSpaceMoves moves) {
  GridProblem p;
  p.dims = b.space->dims();
  p.extent = cells;
  p.cspace = CSpaceQuery{b.space, moves, b.start, b.goal};
  return p;
}

GridReport solve(const GridProblem& p, GridAlgorithm algo, double weight = 2.0) {
  GridSearchOptions o;
  o.algorithm = algo;
  if (algo == GridAlgorithm::wastar) o.weight = weight;
  o.keep_path = true;
  return solve_grid(p, o);
}

// The test's own oracle: every vertex of the lattice enumerated, every move tested with the
// space's one-state test at the motion's samples, Dijkstra (or BFS) from the start vertex.
struct Oracle {
  double cost = std::numeric_limits<double>::infinity();
  std::uint64_t hops = 0;
};
Oracle lattice_oracle(const ConfigSpace& space, int cells, bool pairs, const std::vector<int>& s,
                      const std::vector<int>& g, bool hops_only) {
  const int d = space.dims();
  std::uint64_t n = 1;
  for (int a = 0; a < d; ++a) n *= static_cast<std::uint64_t>(cells);
  auto coords = [&](std::uint64_t i) {
    std::vector<int> c(d);
    for (int a = 0; a < d; ++a, i /= cells) c[a] = static_cast<int>(i % cells);
    return c;
  };
  auto index = [&](const std::vector<int>& c) {
    std::uint64_t i = 0;
    for (int a = d - 1; a >= 0; --a) i = i * cells + c[a];
    return i;
  };
  auto config = [&](const std::vector<int>& c) {
    std::vector<double> q(d);
    for (int a = 0; a < d; ++a) {
      const auto& ax = space.axes()[a];
      q[a] = ax.periodic ? ax.lower + c[a] * (ax.upper - ax.lower) / cells
                         : ax.lower + c[a] * (ax.upper - ax.lower) / (cells - 1);
    }
    return q;
  };
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<std::uint64_t> hop(n, 0);
  using Item = std::pair<double, std::uint64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[index(s)] = 0;
  open.push({0.0, index(s)});
  // Moves as (axis, step) lists: one axis, or (pairs) two.
  std::vector<std::vector<std::pair<int, int>>> moves;
  for (int a = 0; a < d; ++a)
    for (int sa = -1; sa <= 1; sa += 2) moves.push_back({{a, sa}});
  if (pairs)
    for (int a = 0; a < d; ++a)
      for (int b = a + 1; b < d; ++b)
        for (int sa = -1; sa <= 1; sa += 2)
          for (int sb = -1; sb <= 1; sb += 2) moves.push_back({{a, sa}, {b, sb}});
  std::vector<double> samples;
  while (!open.empty()) {
    auto [du, u] = open.top();
    open.pop();
    if (du > dist[u]) continue;
    const auto cu = coords(u);
    const auto qu = config(cu);
    for (const auto& move : moves) {
      auto cv = cu;
      bool inside = true;
      for (const auto& [ax, st] : move) {
        int v = cu[ax] + st;
        if (space.axes()[ax].periodic)
          v = (v + cells) % cells;
        else if (v < 0 || v >= cells)
          inside = false;
        cv[ax] = v;
      }
      if (!inside) continue;
      const auto qv = config(cv);
      const Motion motion(space, qu, qv);
      const std::size_t m = motion.samples(samples);
      bool ok = true;
      for (std::size_t k = 0; k < m && ok; ++k) ok = space.is_valid(samples.data() + k * d);
      if (!ok) continue;
      const std::uint64_t v = index(cv);
      const double w = hops_only ? 1.0 : motion.length();
      if (du + w < dist[v] - 1e-12) {
        dist[v] = du + w;
        hop[v] = hop[u] + 1;
        open.push({dist[v], v});
      }
    }
  }
  return {dist[index(g)], hop[index(g)]};
}

TEST(CSpacePlanning, AStarEqualsTheTestsOwnDijkstraOnSmallChainsAndCubes) {
  struct Case {
    const char* world;
    int dims, cells;
    CSpaceMoves moves;
  };
  for (const Case c :
       {Case{"chain", 3, 16, CSpaceMoves::axes}, Case{"chain", 3, 12, CSpaceMoves::seed_pairs},
        Case{"chain", 4, 8, CSpaceMoves::axes}, Case{"hypercube", 3, 11, CSpaceMoves::seed_pairs},
        Case{"hypercube", 4, 11, CSpaceMoves::axes}}) {
    SCOPED_TRACE(std::string(c.world) + " " + std::to_string(c.dims));
    const BenchmarkSpace b = make_benchmark_space(c.world, c.dims);
    const GridProblem p = cspace_problem(b, c.cells, c.moves);
    const GridReport astar = solve(p, GridAlgorithm::astar);
    const GridReport dijkstra = solve(p, GridAlgorithm::dijkstra);
    const GridReport bfs = solve(p, GridAlgorithm::bfs);
    const GridReport wastar = solve(p, GridAlgorithm::wastar, 2.0);
    ASSERT_TRUE(astar.cspace);
    const CSpaceReport& cs = *astar.cspace;
    const bool pairs = c.moves == CSpaceMoves::seed_pairs;
    const Oracle oracle =
        lattice_oracle(*b.space, c.cells, pairs, astar.problem.start, astar.problem.goal, false);
    const Oracle fewest =
        lattice_oracle(*b.space, c.cells, pairs, astar.problem.start, astar.problem.goal, true);
    const double ends = cs.start_connection + cs.goal_connection;
    if (!std::isfinite(oracle.cost)) {
      EXPECT_EQ(astar.result.status, Status::no_path);
      EXPECT_EQ(dijkstra.result.status, Status::no_path);
      continue;
    }
    ASSERT_EQ(astar.result.status, Status::solved);
    EXPECT_NEAR(astar.result.cost, oracle.cost + ends, 1e-9);
    EXPECT_NEAR(dijkstra.result.cost, oracle.cost + ends, 1e-9);
    EXPECT_TRUE(cs.path_rechecked);
    ASSERT_EQ(bfs.result.status, Status::solved);
    EXPECT_EQ(bfs.result.path.size() - 1, fewest.hops);
    ASSERT_EQ(wastar.result.status, Status::solved);
    EXPECT_GE(wastar.result.cost, astar.result.cost - 1e-9);
    EXPECT_LE(wastar.result.cost - ends, 2.0 * oracle.cost + 1e-9);
    // The path in the space's coordinates: from the start asked to the goal asked.
    ASSERT_FALSE(cs.path.empty());
    for (int a = 0; a < c.dims; ++a) {
      EXPECT_NEAR(cs.path.front()[a], cs.start[a], 1e-12);
      EXPECT_NEAR(cs.path.back()[a], cs.goal[a], 1e-12);
    }
  }
}

// A space defined here, as a user would: a 2D torus of angles whose band |x| < 2 is blocked
// except nowhere, so the only way from x = -2.5 to x = 2.5 crosses the seam at +-pi.
class BandTorus final : public ConfigSpace {
 public:
  BandTorus()
      : ConfigSpace("band_torus",
                    {{-std::numbers::pi, std::numbers::pi, true},
                     {-std::numbers::pi, std::numbers::pi, true}},
                    0.01) {}

 protected:
  bool valid(const double* q) const override { return std::abs(q[0]) >= 2.0; }
};

TEST(CSpacePlanning, APathCrossesThePeriodicSeam) {
  auto space = std::make_shared<BandTorus>();
  GridProblem p;
  p.dims = 2;
  p.extent = 64;
  p.cspace = CSpaceQuery{space, CSpaceMoves::seed_pairs, {-2.5, 0.3}, {2.5, 0.3}};
  const GridReport r = solve(p, GridAlgorithm::astar);
  ASSERT_EQ(r.result.status, Status::solved);
  // Across the seam the way is 2 pi - 5 long; the other way round would cross the band.
  EXPECT_LT(r.result.cost, 2 * std::numbers::pi - 5.0 + 0.25);
  bool crossed = false;
  const auto& path = r.cspace->path;
  for (std::size_t i = 1; i < path.size(); ++i)
    crossed = crossed || std::abs(path[i][0] - path[i - 1][0]) > std::numbers::pi;
  EXPECT_TRUE(crossed) << "the path never wraps from +pi to -pi";
  for (const auto& q : path) EXPECT_GE(std::abs(q[0]), 2.0 - 1e-12);
}

TEST(CSpacePlanning, OffLatticeEndsJoinByCheckedMotions) {
  const BenchmarkSpace b = make_benchmark_space("chain", 4);
  // The benchmark's goal (pi - 0.001, 0, ...) is no vertex of a 16-cell lattice.
  const GridProblem p = cspace_problem(b, 16, CSpaceMoves::seed_pairs);
  const GridReport r = solve(p, GridAlgorithm::astar);
  ASSERT_TRUE(r.cspace);
  EXPECT_GT(r.cspace->goal_connection, 0.0);
  EXPECT_LE(r.cspace->goal_connection, std::sqrt(4.0) * std::numbers::pi / 16 + 1e-9);
  if (r.result.status == Status::solved) {
    EXPECT_TRUE(r.cspace->path_rechecked);
    // Every motion of the path, tested here one sample at a time.
    std::vector<double> samples;
    for (std::size_t i = 1; i < r.cspace->path.size(); ++i) {
      const Motion m(*b.space, r.cspace->path[i - 1], r.cspace->path[i]);
      const std::size_t k = m.samples(samples);
      for (std::size_t j = 0; j < k; ++j) EXPECT_TRUE(b.space->is_valid(samples.data() + j * 4));
    }
  }
}

TEST(CSpacePlanning, BadInputIsRefusedWithOneLine) {
  const BenchmarkSpace b = make_benchmark_space("hypercube", 3);
  auto expect_input_error = [](const GridProblem& p, GridSearchOptions o, const char* what) {
    try {
      solve_grid(p, o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  GridProblem p = cspace_problem(b, 11, CSpaceMoves::seed_pairs);
  p.cspace->start = {0.5, 0.5, 0.5};  // the cube's middle: no edge's slab holds it
  expect_input_error(p, {}, "a start in collision");
  p = cspace_problem(b, 11, CSpaceMoves::seed_pairs);
  p.cspace->goal = {1.0, 1.0};
  expect_input_error(p, {}, "a goal of the wrong size");
  p = cspace_problem(b, 11, CSpaceMoves::seed_pairs);
  p.cspace->goal = {1.0, 1.0, 1.5};
  expect_input_error(p, {}, "a goal outside the bounds");
  p = cspace_problem(b, 1, CSpaceMoves::seed_pairs);
  expect_input_error(p, {}, "one cell");
  p = cspace_problem(b, 11, CSpaceMoves::seed_pairs);
  GridSearchOptions dense;
  dense.engine = GridEngine::dense;
  expect_input_error(p, dense, "the dense engine");
  EXPECT_THROW(make_benchmark_space("chain", 1), InputError);
  EXPECT_THROW(make_benchmark_space("chain", 17), InputError);
  EXPECT_THROW(make_benchmark_space("arm", 4), InputError);
}

TEST(CSpacePlanning, ChecksGoInBatches) {
  const BenchmarkSpace b = make_benchmark_space("chain", 5);
  const GridReport r = solve(cspace_problem(b, 20, CSpaceMoves::seed_pairs), GridAlgorithm::astar);
  ASSERT_TRUE(r.cspace);
  ASSERT_GT(r.result.counters.expanded, 0u);
  // About two batches per expansion (ends, then edges), each of many states.
  EXPECT_LE(r.cspace->batches, 2 * r.result.counters.expanded + 8);
  EXPECT_GT(r.result.counters.collision_checks, 4 * r.cspace->batches);
}

}  // namespace
}  // namespace hpcplan

namespace hpcplan {
namespace {

// The batches change how states are tested, never which or with what answer: the same search,
// state for state, as one-at-a-time checks.
TEST(CSpacePlanning, BatchAndSingleChecksGiveTheSameSearch) {
  for (const char* world : {"chain", "hypercube"}) {
    const BenchmarkSpace b = make_benchmark_space(world, 5);
    GridProblem p = cspace_problem(b, b.cells, CSpaceMoves::seed_pairs);
    const GridReport batch = solve(p, GridAlgorithm::astar);
    p.cspace->batch_checks = false;
    const GridReport single = solve(p, GridAlgorithm::astar);
    ASSERT_EQ(batch.result.status, Status::solved);
    EXPECT_EQ(batch.result.cost, single.result.cost);
    EXPECT_EQ(batch.result.counters.expanded, single.result.counters.expanded);
    EXPECT_EQ(batch.result.counters.collision_checks, single.result.counters.collision_checks);
    EXPECT_EQ(batch.cspace->path, single.cspace->path);
    EXPECT_GT(batch.cspace->batches, 0u);
    EXPECT_EQ(single.cspace->batches, 0u);
  }
}

}  // namespace
}  // namespace hpcplan

namespace hpcplan {
namespace {

// What a review found (each case failed before its fix): a step so fine that the motion's
// sample count overflowed (paths through obstacles, reported solved), a start tested before it
// was wrapped, start = goal reported as a round trip, a goal on a bounded axis's upper face
// offered one candidate vertex, and the last vertex of a bounded axis a rounding past its bound.
class Strip final : public ConfigSpace {
 public:
  Strip(double lower, double upper, double mid)
      : ConfigSpace("strip", {{lower, upper, false}, {lower, upper, false}}, 0.001), mid_(mid) {}

 protected:
  // Free except a wall along the upper face in x, open only within 0.02 of y = mid; nothing
  // past the upper bound (a vertex rounded past it would be in collision).
  bool valid(const double* q) const override {
    const double top = axes()[0].upper;
    return !(q[0] >= top - 0.03 && std::abs(q[1] - mid_) >= 0.02) && q[0] <= top && q[1] <= top;
  }

 private:
  double mid_;
};

TEST(CSpacePlanning, ReviewedEdgeCases) {
  EXPECT_THROW(make_benchmark_space("hypercube", 3, 1e-300), InputError);
  EXPECT_THROW(make_benchmark_space("chain", 4, 1e-9), InputError);

  // An angle of 1e300 is tested as the angle it wraps to, and planned from it.
  const BenchmarkSpace chain = make_benchmark_space("chain", 4);
  GridProblem p = cspace_problem(chain, 16, CSpaceMoves::seed_pairs);
  p.cspace->start[1] += 2 * std::numbers::pi * 1e6;
  const GridReport wrapped = solve(p, GridAlgorithm::astar);
  const GridReport plain =
      solve(cspace_problem(chain, 16, CSpaceMoves::seed_pairs), GridAlgorithm::astar);
  EXPECT_EQ(wrapped.result.status, plain.result.status);
  EXPECT_NEAR(wrapped.result.cost, plain.result.cost, 1e-6);

  // Start = goal: that state, no move.
  const BenchmarkSpace cube = make_benchmark_space("hypercube", 3);
  p = cspace_problem(cube, 11, CSpaceMoves::seed_pairs);
  p.cspace->start = p.cspace->goal = {0.05, 0.05, 0.05};
  const GridReport same = solve(p, GridAlgorithm::astar);
  EXPECT_EQ(same.result.status, Status::solved);
  EXPECT_EQ(same.result.cost, 0.0);
  EXPECT_EQ(same.result.hops, 0u);

  // A goal on the upper face whose two face vertices are walled off joins one of the cell's
  // inner corners (the face offered only the face's vertices before).
  p = GridProblem{};
  p.dims = 2;
  p.extent = 11;
  p.cspace = CSpaceQuery{
      std::make_shared<Strip>(0.0, 1.0, 0.45), CSpaceMoves::seed_pairs, {0.5, 0.5}, {1.0, 0.45}};
  const GridReport face = solve(p, GridAlgorithm::astar);
  EXPECT_EQ(face.result.status, Status::solved) << face.cspace->unconnected;

  // The top vertex of a bounded axis is the bound itself: on (-1, 0.3) with 5 cells,
  // -1 + 4 * 0.325 rounds to 0.30000000000000004.
  p.extent = 5;
  p.cspace = CSpaceQuery{
      std::make_shared<Strip>(-1.0, 0.3, 0.3), CSpaceMoves::seed_pairs, {-1.0, -1.0}, {0.3, 0.3}};
  const GridReport top = solve(p, GridAlgorithm::astar);
  ASSERT_EQ(top.result.status, Status::solved) << top.cspace->unconnected;
  for (const auto& q : top.cspace->path)
    for (double v : q) EXPECT_LE(v, 0.3);
}

}  // namespace
}  // namespace hpcplan
