// Every grid algorithm against the independent oracle on random small instances.
#include <gtest/gtest.h>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "lattice_oracle.hpp"

namespace {

using namespace hpcplan;

struct Instance {
  GridProblem problem;
  std::vector<int> start, goal;
};

int small_extent(int d) {
  static const int extents[] = {0, 60, 60, 20, 10, 7, 5};
  return extents[d];
}

Instance random_instance(std::uint64_t seed, int d, bool full) {
  SplitMix64 rng(seed);
  Instance in;
  GridProblem& p = in.problem;
  p.dims = d;
  p.extent = small_extent(d);
  p.gog.seed = rng.next();
  p.gog.shift_v = static_cast<int>(rng.next_below(3));
  p.gog.shift_p = static_cast<int>(rng.next_below(5));
  // One instance in four is dense enough that start and goal are often cut apart, so the
  // no-path answer is checked against the oracle too.
  p.gog.density = seed % 4 == 3 ? 0.6 + 0.2 * rng.next_unit() : 0.15 + 0.4 * rng.next_unit();
  p.connectivity = full ? Connectivity::full : Connectivity::seed_pairs;
  const GogField field(d, p.extent, p.gog);
  auto draw_free = [&] {
    for (;;) {
      std::vector<int> s(d);
      for (auto& c : s) c = static_cast<int>(rng.next_below(p.extent));
      if (field.is_free(s)) return s;
    }
  };
  in.start = draw_free();
  in.goal = draw_free();
  p.start = in.start;
  p.goal = in.goal;
  return in;
}

GridReport run(const Instance& in, GridAlgorithm algo, HeuristicKind h = HeuristicKind::lattice,
               double weight = 1.0, GridEngine engine = GridEngine::sparse) {
  GridSearchOptions o;
  o.algorithm = algo;
  o.engine = engine;
  o.heuristic = h;
  if (algo == GridAlgorithm::wastar) o.weight = weight;
  o.keep_path = true;
  return solve_grid(in.problem, o);
}

// Independent re-validation of a returned path: endpoints, legal moves, reported length.
void expect_valid_path(const GridReport& r, const oracle::Lattice& o, const Instance& in) {
  ASSERT_EQ(r.result.status, search::Status::solved);
  ASSERT_FALSE(r.result.path.empty());
  EXPECT_EQ(r.result.path.front(), in.start);
  EXPECT_EQ(r.result.path.back(), in.goal);
  EXPECT_EQ(r.result.hops + 1, r.result.path.size());
  std::size_t illegal = 0;
  const double length = o.path_length(r.result.path, &illegal);
  ASSERT_GE(length, 0) << "illegal move at step " << illegal;
  EXPECT_NEAR(length, r.result.cost, 1e-9);
}

class OracleAgreement : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(OracleAgreement, EveryAlgorithmMatchesTheOracle) {
  const auto [d, trial, full] = GetParam();
  const Instance in = random_instance(1000 * d + trial + (full ? 7777 : 0), d, full);
  const GogField field(d, in.problem.extent, in.problem.gog);
  const oracle::Lattice o(field, full);
  const oracle::Answer best = o.dijkstra(in.start, in.goal);
  const oracle::Answer fewest = o.bfs(in.start, in.goal);
  ASSERT_EQ(best.reachable, fewest.reachable);

  const GridReport astar = run(in, GridAlgorithm::astar);
  const GridReport astar_euclid = run(in, GridAlgorithm::astar, HeuristicKind::euclidean);
  const GridReport dijkstra = run(in, GridAlgorithm::dijkstra);
  const GridReport bfs = run(in, GridAlgorithm::bfs);
  // The same two on the dense engine.
  const GridReport dense_dijkstra =
      run(in, GridAlgorithm::dijkstra, HeuristicKind::lattice, 1.0, GridEngine::dense);
  const GridReport dense_bfs =
      run(in, GridAlgorithm::bfs, HeuristicKind::lattice, 1.0, GridEngine::dense);
  ASSERT_EQ(dense_bfs.options.engine, "dense");
  if (!best.reachable) {
    for (const auto* r : {&astar, &astar_euclid, &dijkstra, &bfs, &dense_dijkstra, &dense_bfs})
      EXPECT_EQ(r->result.status, search::Status::no_path);
    return;
  }
  for (const auto* r : {&astar, &astar_euclid, &dijkstra, &dense_dijkstra}) {
    expect_valid_path(*r, o, in);
    EXPECT_NEAR(r->result.cost, best.cost, 1e-9 * (1 + best.cost));
  }
  // The exact heuristic never expands more than Dijkstra.
  EXPECT_LE(astar.result.counters.expanded, dijkstra.result.counters.expanded);
  for (const auto* r : {&bfs, &dense_bfs}) {
    expect_valid_path(*r, o, in);
    EXPECT_EQ(static_cast<std::int64_t>(r->result.hops), fewest.hops);
    EXPECT_LE(r->result.hops, astar.result.hops);
  }
  for (double w : {1.5, 3.0}) {
    const GridReport wa = run(in, GridAlgorithm::wastar, HeuristicKind::lattice, w);
    expect_valid_path(wa, o, in);
    EXPECT_LE(wa.result.cost, w * best.cost + 1e-9);
    EXPECT_GE(wa.result.cost, best.cost - 1e-9);
  }
}

// The instances below, counted: the agreement test compares costs only where a path exists, so
// most instances must have one (and some none, so the no-path branch runs too).
TEST(OracleAgreementInstances, MostAreSolvableAndSomeAreNot) {
  int reachable = 0, total = 0;
  for (int d = 2; d < 7; ++d)
    for (int trial = 0; trial < 12; ++trial) {
      const Instance in = random_instance(1000 * d + trial, d, false);
      const GogField field(d, in.problem.extent, in.problem.gog);
      reachable += oracle::Lattice(field, false).bfs(in.start, in.goal).reachable;
      ++total;
    }
  EXPECT_EQ(total, 60);
  EXPECT_GE(reachable, 40);
  EXPECT_LT(reachable, total);
}

// 5 dimensions x 12 trials on the seed rule, plus full connectivity for d <= 4.
INSTANTIATE_TEST_SUITE_P(SeedRule, OracleAgreement,
                         ::testing::Combine(::testing::Range(2, 7), ::testing::Range(0, 12),
                                            ::testing::Values(false)));
INSTANTIATE_TEST_SUITE_P(FullConnectivity, OracleAgreement,
                         ::testing::Combine(::testing::Range(2, 5), ::testing::Range(0, 4),
                                            ::testing::Values(true)));

}  // namespace
