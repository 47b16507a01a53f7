#include <gtest/gtest.h>

#include "support/walled_line.hpp"

#include "hpcplan/core/error.hpp"
#include "hpcplan/graph/lattice_distance.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"

namespace {

using namespace hpcplan;

using hpcplan::test_support::walled_line;

TEST(GridPlanner, WallGivesNoPathForEveryAlgorithm) {
  const GridProblem p = walled_line();
  for (auto algo :
       {GridAlgorithm::astar, GridAlgorithm::wastar, GridAlgorithm::dijkstra, GridAlgorithm::bfs}) {
    GridSearchOptions o;
    o.algorithm = algo;
    const GridReport r = solve_grid(p, o);
    EXPECT_EQ(r.result.status, search::Status::no_path);
    EXPECT_TRUE(r.result.path.empty());
  }
}

TEST(GridPlanner, TinyBudgetIsReportedNotCrashed) {
  GridProblem p;
  p.dims = 4;
  GridSearchOptions o;
  o.max_states = 10;
  const GridReport r = solve_grid(p, o);
  EXPECT_EQ(r.result.status, search::Status::budget_exceeded);
  EXPECT_LE(r.result.counters.peak_states, 11u);
}

TEST(GridPlanner, DefaultProblemsAreSolvedWithTheLatticeQualityLimit) {
  for (int d = 2; d <= 10; d += 2) {
    GridProblem p;
    p.dims = d;
    const GridReport r = solve_grid(p, GridSearchOptions{});
    ASSERT_EQ(r.result.status, search::Status::solved) << "d=" << d;
    EXPECT_GT(r.problem.blocked_fraction, 0.25);
    // A lattice path cannot beat the free-space lattice distance between the states used.
    std::vector<int> delta(d);
    for (int i = 0; i < d; ++i) delta[i] = std::abs(r.problem.goal[i] - r.problem.start[i]);
    EXPECT_GE(r.result.cost, seed_rule_free_distance(delta).value() - 1e-9);
  }
}

TEST(GridPlanner, DefaultCornersAreAdjustedOneAxisStepAtATime) {
  int adjusted = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    GridProblem p;
    p.dims = 3;
    p.gog.seed = seed;
    p.gog.density = 0.6;
    const GogField f(3, 100, p.gog);
    GridSearchOptions o;
    o.max_states = 1;  // only the set-up matters here
    const GridReport r = solve_grid(p, o);
    EXPECT_TRUE(f.is_free(r.problem.start));
    EXPECT_TRUE(f.is_free(r.problem.goal));
    // Replay the walk: every state before the reported one must be blocked.
    std::vector<int> s(3, 0);
    for (int step = 0; s != r.problem.start; ++step) {
      ASSERT_FALSE(f.is_free(s));
      ++s[step % 3];
      ASSERT_LE(step, 300);
    }
    adjusted += r.problem.start_adjusted;
  }
  EXPECT_GT(adjusted, 5);
}

TEST(GridPlanner, StartEqualsGoalCostsNothing) {
  GridProblem p;
  p.dims = 3;
  p.gog.threshold = 10;
  p.start = std::vector<int>{4, 4, 4};
  p.goal = p.start;
  GridSearchOptions o;
  o.keep_path = true;
  const GridReport r = solve_grid(p, o);
  EXPECT_EQ(r.result.status, search::Status::solved);
  EXPECT_EQ(r.result.cost, 0.0);
  EXPECT_EQ(r.result.quality, 1.0);
  EXPECT_EQ(r.result.path.size(), 1u);
}

TEST(GridPlanner, BadInputIsAnInputError) {
  auto expect_bad = [](GridProblem p, GridSearchOptions o = {}) {
    EXPECT_THROW(solve_grid(p, o), InputError);
  };
  GridProblem p;
  p.dims = 0;
  expect_bad(p);
  p.dims = 17;
  expect_bad(p);
  p.dims = 2;
  p.extent = 1;
  expect_bad(p);
  p.extent = 70000;
  expect_bad(p);
  p.extent = 100;
  p.start = std::vector<int>{1, 2, 3};
  expect_bad(p);
  p.start = std::vector<int>{1, 100};
  expect_bad(p);
  p.start.reset();
  p.connectivity = Connectivity::full;
  p.dims = 5;
  expect_bad(p);
  p.connectivity = Connectivity::seed_pairs;
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::wastar;
  o.weight = 0.5;
  expect_bad(p, o);
  o.algorithm = GridAlgorithm::astar;
  o.weight = 2.0;
  expect_bad(p, o);
  EXPECT_THROW(parse_grid_algorithm("dfs"), InputError);
  EXPECT_THROW(parse_coordinates("1,,2", "--start"), InputError);
  EXPECT_THROW(parse_coordinates("1,x", "--start"), InputError);
  EXPECT_THROW(parse_coordinates("", "--start"), InputError);
  EXPECT_EQ(parse_coordinates("3,-4,5", "--start"), (std::vector<int>{3, -4, 5}));
}

TEST(GridPlanner, StartInsideAnObstacleIsRejected) {
  GridProblem p;
  p.dims = 2;
  const GogField f(2, 100, p.gog);
  for (int x = 0; x < 100; ++x)
    if (!f.is_free(std::vector<int>{x, 50})) {
      p.start = std::vector<int>{x, 50};
      break;
    }
  ASSERT_TRUE(p.start.has_value());
  try {
    solve_grid(p, GridSearchOptions{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inside an obstacle"), std::string::npos);
  }
}

// The dense visited store (small lattices) and the hash map give the same search: the same
// cost, path and expansions, for every algorithm and in 2D to 4D; the store is reused across
// runs (its arrays come back from the pool with a new generation), so a second run in the same
// process must not see the first's states.
TEST(GridPlanner, DenseVisitedStoreEqualsTheHashMap) {
  ASSERT_TRUE(dense_visited_fits(2, 100));
  ASSERT_FALSE(dense_visited_fits(4, 100));  // 28 bits
  ASSERT_TRUE(dense_visited_fits(4, 40));
  for (const int dims : {2, 3, 4})
    for (const GridAlgorithm a :
         {GridAlgorithm::astar, GridAlgorithm::dijkstra, GridAlgorithm::wastar, GridAlgorithm::bfs})
      for (const std::uint64_t seed : {1u, 7u}) {
        GridProblem p;
        p.dims = dims;
        p.extent = dims == 2 ? 100 : dims == 3 ? 40 : 14;
        p.gog.seed = seed;
        GridSearchOptions o;
        o.algorithm = a;
        o.keep_path = true;
        o.engine = GridEngine::sparse;  // the sparse engine's two stores
        const GridReport hash = solve_grid_with<search::DefaultVisitedMap>(p, o);
        const GridReport dense = solve_grid(p, o), again = solve_grid(p, o);
        EXPECT_EQ(hash.options.visited_map, search::DefaultVisitedMap::name);
        EXPECT_EQ(dense.options.visited_map, search::StampedDensePolicy::name);
        for (const GridReport* r : {&dense, &again}) {
          EXPECT_EQ(r->result.status, hash.result.status) << dims << "D " << to_string(a);
          EXPECT_EQ(r->result.cost, hash.result.cost) << dims << "D " << to_string(a);
          EXPECT_EQ(r->result.path, hash.result.path) << dims << "D " << to_string(a);
          EXPECT_EQ(r->result.counters.expanded, hash.result.counters.expanded)
              << dims << "D " << to_string(a);
        }
      }
}

TEST(GridPlanner, DenseStoreChoiceRefusesImpossibleLattices) {
  EXPECT_FALSE(dense_visited_fits(0, 10));
  EXPECT_FALSE(dense_visited_fits(17, 10));
  EXPECT_FALSE(dense_visited_fits(2, 1));
  EXPECT_FALSE(dense_visited_fits(2, 70000));
  EXPECT_TRUE(dense_visited_fits(2, 8192));
  EXPECT_FALSE(dense_visited_fits(2, 8193));  // 14 bits per axis: 28
}

}  // namespace
