// Distributed grid search against the serial engine. The binary runs under
// mpirun -np P (ctest runs it for P = 1, 2, 4, 8); every rank runs every test, so the
// collective calls match, and checks on the full report are made on rank 0. Tests never stop
// early on one rank only (EXPECT, not ASSERT, around collectives), so a failure cannot turn
// into a hang; ctest's timeout guards the rest.
#include <gtest/gtest.h>

#include "support/walled_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>

#include <unistd.h>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"
#include "hpcplan/dense/slab_plan.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/env/benchmark_spaces.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/partition/ownership.hpp"
#include "hpcplan/partition/rank_simulation.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace {

using namespace hpcplan;

const mpi::Communicator* g_comm = nullptr;
bool root() {
  return g_comm->rank() == 0;
}

// Independent of the engines: consecutive states differ by one step in one or two axes
// (any number for full connectivity) and every corner of the move's unit cell is free.
void expect_valid_path(const GridReport& r, const GridProblem& p) {
  ASSERT_FALSE(r.result.path.empty());
  EXPECT_EQ(r.result.path.front(), r.problem.start);
  EXPECT_EQ(r.result.path.back(), r.problem.goal);
  const GogField field(p.dims, p.extent, p.gog);
  double length = 0.0;
  for (std::size_t i = 1; i < r.result.path.size(); ++i) {
    std::vector<int> axes;
    for (int a = 0; a < p.dims; ++a) {
      const int diff = r.result.path[i][a] - r.result.path[i - 1][a];
      ASSERT_LE(std::abs(diff), 1);
      if (diff != 0) axes.push_back(a);
    }
    ASSERT_FALSE(axes.empty());
    if (p.connectivity == Connectivity::seed_pairs) {
      ASSERT_LE(axes.size(), 2u);
    }
    for (unsigned subset = 0; subset < (1u << axes.size()); ++subset) {
      std::vector<int> corner = r.result.path[i - 1];
      for (std::size_t j = 0; j < axes.size(); ++j)
        if (subset & (1u << j)) corner[axes[j]] = r.result.path[i][axes[j]];
      ASSERT_TRUE(field.is_free(corner)) << "path crosses an obstacle at step " << i;
    }
    length += std::sqrt(static_cast<double>(axes.size()));
  }
  EXPECT_NEAR(length, r.result.cost, 1e-9 * (1 + r.result.cost));
}

int extent_for(int d) {
  static const int table[] = {0, 0, 40, 16, 9, 6, 5, 4, 4};
  return table[d];
}

struct Config {
  const char* algo;
  distributed::Scheme scheme;
  int coarsen;
  int slabs = 0;      // slab width; 0 = hash ownership
  bool cuts = false;  // prefix cuts spaced evenly over the positions (one per extra rank)
};

// P - 1 prefix cuts spaced evenly over a lattice's extent^2 positions.
std::vector<std::uint32_t> even_cuts(int extent, int ranks) {
  std::vector<std::uint32_t> cuts;
  const auto n = static_cast<std::uint32_t>(extent * extent);
  for (int j = 1; j < ranks; ++j) cuts.push_back(std::max<std::uint32_t>(j, n * j / ranks));
  return cuts;
}

TEST(Distributed, RandomInstancesMatchTheSerialEngine) {
  const Config configs[] = {
      {"astar", distributed::Scheme::async, 0},
      {"astar", distributed::Scheme::bulk_sync, 0},
      {"astar", distributed::Scheme::async, 1},
      {"dijkstra", distributed::Scheme::async, 0},
      {"dijkstra", distributed::Scheme::bulk_sync, 1},
      {"wastar", distributed::Scheme::async, 0},
      {"wastar", distributed::Scheme::bulk_sync, 0},
      {"bfs", distributed::Scheme::level_sync, 0},
      {"bfs", distributed::Scheme::level_sync, 1},
      // Slabs of width 1 (every layer changes owner: most traffic) and 2 (dealt round the
      // ranks, so at 8 ranks some own nothing on the smaller extents).
      {"astar", distributed::Scheme::async, 0, 2},
      {"dijkstra", distributed::Scheme::bulk_sync, 0, 1},
      {"wastar", distributed::Scheme::async, 0, 1},
      {"bfs", distributed::Scheme::level_sync, 0, 2},
      // Slabs of 3: most states have their whole neighbourhood on their rank, and their
      // successors skip the owner look-up.
      {"dijkstra", distributed::Scheme::async, 0, 3},
      // Prefix cuts: the boundary runs along two axes.
      {"astar", distributed::Scheme::async, 0, 0, true},
      {"dijkstra", distributed::Scheme::bulk_sync, 0, 0, true},
  };
  SplitMix64 rng(2026);
  int solved = 0, compared = 0;
  for (int d = 2; d <= 8; ++d) {
    for (int instance = 0; instance < 2; ++instance) {
      GridProblem p;
      p.dims = d;
      p.extent = extent_for(d);
      p.gog.seed = rng.next();
      p.gog.density = 0.3 + 0.4 * rng.next_unit();
      if (d <= 3 && instance == 1) p.connectivity = Connectivity::full;
      for (const Config& c : configs) {
        GridSearchOptions o;
        o.algorithm = parse_grid_algorithm(c.algo);
        o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
        o.keep_path = true;
        if (o.algorithm == GridAlgorithm::wastar) o.weight = 1.8;
        distributed::DistGridOptions dopt;
        dopt.scheme =
            c.scheme == distributed::Scheme::level_sync ? distributed::Scheme::async : c.scheme;
        dopt.coarsen_shift = c.coarsen;
        dopt.slab_width = c.slabs;
        if (c.cuts) dopt.prefix_cuts = even_cuts(p.extent, g_comm->size());
        dopt.batch = 1 + rng.next_below(64);  // small batches: many messages in flight
        const GridReport r = distributed::solve_grid_distributed(p, o, dopt, *g_comm);
        if (!root()) continue;
        GridSearchOptions so = o;
        if (o.algorithm == GridAlgorithm::wastar) {
          so.algorithm = GridAlgorithm::astar;
          so.weight.reset();
        }
        const GridReport s = solve_grid(p, so);  // the optimum (or fewest hops for BFS)
        SCOPED_TRACE(::testing::Message()
                     << "d=" << d << " seed=" << p.gog.seed << " algo=" << c.algo << " scheme="
                     << r.distribution.scheme << " coarsen=" << c.coarsen << " slabs=" << c.slabs
                     << " cuts=" << c.cuts << " ranks=" << r.distribution.ranks);
        ++compared;
        EXPECT_EQ(r.result.status, s.result.status);
        if (r.result.status != search::Status::solved || s.result.status != search::Status::solved)
          continue;
        ++solved;
        expect_valid_path(r, p);
        if (o.algorithm == GridAlgorithm::bfs) {
          EXPECT_EQ(r.result.hops, s.result.hops);
        } else if (o.algorithm == GridAlgorithm::wastar) {
          EXPECT_GE(r.result.cost, s.result.cost - 1e-9);
          EXPECT_LE(r.result.cost, 1.8 * s.result.cost + 1e-9);
        } else {
          EXPECT_NEAR(r.result.cost, s.result.cost, 1e-9 * (1 + s.result.cost));
        }
        std::uint64_t expanded = 0;
        for (const auto& k : r.distribution.per_rank) expanded += k.expanded;
        EXPECT_EQ(expanded, r.result.counters.expanded);
        EXPECT_EQ(r.distribution.per_rank.size(), static_cast<std::size_t>(g_comm->size()));
      }
    }
  }
  if (root()) {
    std::printf("compared %d distributed runs with serial, %d solved\n", compared, solved);
    EXPECT_GE(compared, 100);
    EXPECT_GE(solved, compared / 2) << "too few solvable instances to mean anything";
  }
}

using hpcplan::test_support::walled_line;

TEST(Distributed, NoPathIsAgreedByEveryRankForEveryScheme) {
  const GridProblem p = walled_line();
  for (const char* algo : {"astar", "wastar", "dijkstra", "bfs"})
    for (auto scheme : {distributed::Scheme::async, distributed::Scheme::bulk_sync}) {
      GridSearchOptions o;
      o.algorithm = parse_grid_algorithm(algo);
      o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
      distributed::DistGridOptions d;
      d.scheme = scheme;
      const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
      // Every rank learns the outcome, not only rank 0.
      EXPECT_EQ(r.result.status, search::Status::no_path) << algo;
    }
}

TEST(Distributed, BudgetExceededStopsEveryRank) {
  GridProblem p;
  p.dims = 4;
  p.extent = 30;
  for (const char* algo : {"dijkstra", "bfs", "astar"})
    for (auto scheme : {distributed::Scheme::async, distributed::Scheme::bulk_sync}) {
      GridSearchOptions o;
      o.algorithm = parse_grid_algorithm(algo);
      o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
      o.max_states = 2000;
      distributed::DistGridOptions d;
      d.scheme = scheme;
      const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
      EXPECT_EQ(r.result.status, search::Status::budget_exceeded) << algo;
      if (root()) {
        for (const auto& k : r.distribution.per_rank)
          EXPECT_LE(k.states_stored, 2000u / g_comm->size() + 2) << algo;
      }
    }
}

// A limit no machine can meet (1 ns): every rank stops at its first look at the clock, which
// comes every 1,024 expansions and after every slice, so no rank expands more than that plus
// one slice (what stopped the search is the count, not how fast this machine is).
TEST(Distributed, TimeLimitStopsEveryRank) {
  GridProblem p;
  p.dims = 6;
  p.extent = 40;  // millions of states
  for (auto scheme : {distributed::Scheme::async, distributed::Scheme::bulk_sync}) {
    GridSearchOptions o;
    o.algorithm = GridAlgorithm::dijkstra;
    o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
    o.time_limit_s = 1e-9;
    distributed::DistGridOptions d;
    d.scheme = scheme;
    const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
    EXPECT_EQ(r.result.status, search::Status::timeout);
    if (root()) {
      ASSERT_EQ(r.distribution.per_rank.size(), static_cast<std::size_t>(g_comm->size()));
      const std::uint64_t slice = scheme == distributed::Scheme::async ? 64 : d.sync_every;
      for (const search::RankCounters& k : r.distribution.per_rank)
        EXPECT_LE(k.expanded, 1024 + slice);
    }
  }
}

// The rank simulator's prediction against this very run: per-rank expansions and the
// successors that crossed ranks (sent + filtered duplicates), for both ownership hashes.
// Dijkstra under the bulk-synchronous schedule with short rounds (16 expansions) expands
// almost exactly the serial set, so the prediction must be close; the tolerance covers the few
// extra expansions of a parallel order. (With 4096-expansion rounds this small problem sees
// 1.26x search overhead at P = 8: the ranks expand past the goal before the incumbent
// arrives, which the simulator, observing the serial order, does not model.)
TEST(Distributed, RankSimulatorPredictsTheRealSplit) {
  const int p_ranks = g_comm->size();
  GridProblem p;
  p.dims = 4;
  p.extent = 14;
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::dijkstra;
  o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
  for (int k : {0, 1}) {
    const partition::RankSimulation sim = partition::simulate_ranks(p, o, {p_ranks}, {k});
    distributed::DistGridOptions d;
    d.scheme = distributed::Scheme::bulk_sync;
    d.coarsen_shift = k;
    d.sync_every = 16;
    const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
    if (!root()) continue;
    ASSERT_EQ(sim.splits.size(), 1u);
    const auto& s = sim.splits[0];
    ASSERT_EQ(r.distribution.per_rank.size(), static_cast<std::size_t>(p_ranks));
    const double total = static_cast<double>(sim.serial.result.counters.expanded);
    std::uint64_t remote = 0;
    for (int rank = 0; rank < p_ranks; ++rank) {
      const auto& real = r.distribution.per_rank[rank];
      EXPECT_NEAR(static_cast<double>(real.expanded), static_cast<double>(s.expanded[rank]),
                  0.02 * total)
          << "rank " << rank << " k " << k;
      remote += real.records_sent + real.records_filtered;
    }
    EXPECT_NEAR(static_cast<double>(remote), static_cast<double>(s.remote_successors),
                0.03 * static_cast<double>(s.remote_successors) + 10)
        << "k " << k;
    EXPECT_NEAR(partition::deviation_percent(s.expanded), s.expansion_deviation_percent, 1e-12);
  }
}

TEST(Distributed, StartEqualsGoal) {
  GridProblem p;
  p.dims = 3;
  p.extent = 10;
  const GogField field(3, 10, p.gog);
  std::vector<int> free{0, 0, 0};
  while (!field.is_free(free)) ++free[0];
  p.start = free;
  p.goal = free;
  for (const char* algo : {"astar", "bfs"}) {
    GridSearchOptions o;
    o.algorithm = parse_grid_algorithm(algo);
    o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
    const GridReport r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
    EXPECT_EQ(r.result.status, search::Status::solved);
    EXPECT_EQ(r.result.cost, 0.0);
    EXPECT_EQ(r.result.hops, 0u);
  }
}

// Configuration spaces (OMPL's kinematic chain and hypercube): every rank count and schedule
// gives the serial engine's cost (which the unit tests check against their own Dijkstra), BFS
// its fewest moves, and rank 0's path is re-checked motion by motion (path_rechecked).
TEST(CSpaceRanks, ChainAndHypercubeGiveTheSerialCost) {
  struct Case {
    const char* world;
    int dims, cells;
  };
  // (Small: at 8 ranks on the 2-core VM every exchange is a context switch; chain 5 and a
  // bulk exchange every 64 expansions made this test 24 s there.)
  for (const Case c : {Case{"chain", 4, 16}, Case{"hypercube", 4, 11}}) {
    const BenchmarkSpace b = make_benchmark_space(c.world, c.dims);
    GridProblem p;
    p.dims = c.dims;
    p.extent = c.cells;
    p.cspace = CSpaceQuery{b.space, CSpaceMoves::seed_pairs, b.start, b.goal};
    for (const char* algo : {"astar", "dijkstra", "bfs", "wastar"}) {
      for (const char* mode : {"async", "bulk"}) {
        if (std::string(algo) == "bfs" && std::string(mode) == "bulk") continue;  // level-sync
        SCOPED_TRACE(std::string(c.world) + " " + std::to_string(c.dims) + " " + algo + " " + mode);
        GridSearchOptions o;
        o.algorithm = parse_grid_algorithm(algo);
        distributed::DistGridOptions d;
        d.scheme = distributed::parse_scheme(mode);
        d.sync_every = 256;
        const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
        ASSERT_EQ(r.result.status, search::Status::solved);
        if (g_comm->rank() != 0) continue;
        const GridReport serial = solve_grid(p, o);
        ASSERT_EQ(serial.result.status, search::Status::solved);
        ASSERT_TRUE(r.cspace);
        EXPECT_TRUE(r.cspace->path_rechecked);
        if (o.algorithm == GridAlgorithm::wastar) {
          const GridReport optimal = solve_grid(p, GridSearchOptions{});
          EXPECT_LE(r.result.cost, 2.0 * optimal.result.cost + 1e-9);
          EXPECT_GE(r.result.cost, optimal.result.cost - 1e-9);
        } else if (o.algorithm == GridAlgorithm::bfs) {
          EXPECT_EQ(r.result.hops, serial.result.hops);
        } else {
          EXPECT_NEAR(r.result.cost, serial.result.cost, 1e-9);
        }
        EXPECT_EQ(r.distribution.ranks, g_comm->size());
      }
    }
  }
}

// The dense engine's slabs: every rank count gives the serial dense engine's answer, path and
// counts (so the walk back crosses slab faces correctly), which the oracle-checked serial
// engine vouches for; from 1D up, with extents that leave some ranks few or no layers, and 1 or
// 2 threads per rank. From 4D up these lattices have fewer layers than 16 per worker, so the
// cut moves below the last axis and the ranks trade halos over several axes through MPI.
TEST(DenseSlabs, EveryRankCountGivesTheSerialAnswerPathAndCounts) {
  SplitMix64 rng(4242);
  int solved = 0, compared = 0;
  const int extents[] = {0, 300, 40, 17, 9, 6, 5};
  for (int d = 1; d <= 6; ++d)
    for (int instance = 0; instance < 3; ++instance) {
      GridProblem p;
      p.dims = d;
      p.extent = extents[d];
      p.gog.seed = rng.next();
      p.gog.density = 0.25 + 0.4 * rng.next_unit();
      if (d <= 3 && instance == 2) p.connectivity = Connectivity::full;
      for (const char* algo : {"bfs", "dijkstra"})
        for (int threads : {1, 2}) {
          GridSearchOptions o;
          o.algorithm = parse_grid_algorithm(algo);
          o.engine = GridEngine::dense;
          o.keep_path = true;
          o.threads = threads;
          const GridReport r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
          if (!root()) continue;
          GridSearchOptions so = o;
          so.threads = 1;
          const GridReport s = solve_grid(p, so);
          SCOPED_TRACE(::testing::Message()
                       << "d=" << d << " seed=" << p.gog.seed << " " << algo
                       << " threads=" << threads << " ranks=" << g_comm->size());
          ++compared;
          EXPECT_EQ(r.options.engine, "dense");
          EXPECT_EQ(r.distribution.scheme, g_comm->size() == 1 ? "serial" : "dense_slabs");
          EXPECT_EQ(r.result.status, s.result.status);
          EXPECT_EQ(r.result.cost, s.result.cost);
          EXPECT_EQ(r.result.hops, s.result.hops);
          EXPECT_EQ(r.result.path, s.result.path);
          EXPECT_EQ(r.result.counters.expanded, s.result.counters.expanded);
          EXPECT_EQ(r.result.counters.generated, s.result.counters.generated);
          ASSERT_TRUE(r.dense.has_value());
          EXPECT_EQ(r.dense->rank_sections.size(), static_cast<std::size_t>(g_comm->size()));
          if (d >= 4 && g_comm->size() > 1) {
            EXPECT_LT(r.dense->cut_axis, d - 1);
          }
          std::uint64_t expanded = 0;
          for (const auto& k : r.distribution.per_rank) expanded += k.expanded;
          EXPECT_EQ(expanded, r.result.counters.expanded);
          if (r.result.status == search::Status::solved) {
            ++solved;
            expect_valid_path(r, p);
          }
        }
    }
  if (root()) {
    EXPECT_GE(compared, 70);
    EXPECT_GE(solved, compared / 2);
  }
}

// The dense engine from 9D to 16D (its move-table kernel) on tiny lattices: every rank count
// gives the serial dense engine's answer, path and counts, which
// tests/unit/test_dense_high_dims.cpp checks against the sparse engine and the oracle. (The
// sparse reference here cost rank 0 most of the suite's time under ASan while the other ranks
// waited: a 16D lattice has 512 moves a state.)
TEST(DenseHighDims, EveryRankCountGivesTheSerialAnswer) {
  SplitMix64 rng(91216);
  int solved = 0;
  for (const int d : {9, 12, 16}) {
    GridProblem p;
    p.dims = d;
    p.extent = d == 9 ? 3 : 2;
    p.gog.seed = rng.next();
    // Runs of one cell: with GOG's default runs of 8 so small a lattice has no blocked state.
    p.gog.shift_v = 0;
    p.gog.shift_p = 0;
    p.gog.density = 0.45;
    for (const char* algo : {"bfs", "dijkstra"}) {
      GridSearchOptions o;
      o.algorithm = parse_grid_algorithm(algo);
      o.engine = GridEngine::dense;
      o.keep_path = true;
      o.threads = 1;
      const GridReport r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
      if (!root()) continue;
      const GridReport s = solve_grid(p, o);
      SCOPED_TRACE(::testing::Message()
                   << d << "D seed " << p.gog.seed << " " << algo << " ranks " << g_comm->size());
      EXPECT_EQ(r.options.engine, "dense");
      EXPECT_EQ(r.distribution.scheme, g_comm->size() == 1 ? "serial" : "dense_slabs");
      EXPECT_EQ(r.result.status, s.result.status);
      EXPECT_EQ(r.result.cost, s.result.cost);
      EXPECT_EQ(r.result.hops, s.result.hops);
      EXPECT_EQ(r.result.path, s.result.path);
      EXPECT_EQ(r.result.counters.expanded, s.result.counters.expanded);
      if (r.result.status == search::Status::solved) {
        ++solved;
        expect_valid_path(r, p);
      }
    }
  }
  if (root()) {
    EXPECT_GE(solved, 4);
  }
}

// Four-word keys (16 axes of extent 5,000: 13 bits an axis, four axes a word) through the
// distributed sparse engine: the serial cost, and a legal path.
TEST(WidestKeys, FourWordKeysGiveTheSerialCostOnEveryRankCount) {
  GridProblem p;
  p.dims = 16;
  p.extent = 5000;
  p.gog.density = 0.3;
  // Start and goal high in the lattice (the packed fields' top bits), a diagonal apart across
  // the first and the last word; fields drawn until both are free (every rank draws the same).
  SplitMix64 rng(16016);
  for (int tries = 0; tries < 100 && !p.start; ++tries) {
    p.gog.seed = rng.next();
    const GogField field(p.dims, p.extent, p.gog);
    std::vector<int> start(16, p.extent - 7), goal = start;
    ++goal[0];
    ++goal[15];
    if (field.is_free(start) && field.is_free(goal)) {
      p.start = start;
      p.goal = goal;
    }
  }
  ASSERT_TRUE(p.start.has_value());
  for (const char* algo : {"astar", "dijkstra", "bfs"}) {
    GridSearchOptions o;
    o.algorithm = parse_grid_algorithm(algo);
    o.engine = GridEngine::sparse;
    o.keep_path = true;
    const GridReport r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
    if (!root()) continue;
    const GridReport s = solve_grid(p, o);
    SCOPED_TRACE(::testing::Message() << algo << " ranks " << g_comm->size());
    // EXPECT and continue, never ASSERT: rank 0 leaving the loop early would leave the other
    // ranks waiting in the next algorithm's collective calls.
    EXPECT_EQ(r.options.key_words, 4);
    EXPECT_EQ(r.result.status, search::Status::solved);
    EXPECT_EQ(s.result.status, search::Status::solved);
    if (r.result.status != search::Status::solved || s.result.status != search::Status::solved)
      continue;
    if (o.algorithm == GridAlgorithm::bfs) {
      EXPECT_EQ(r.result.hops, s.result.hops);
    } else {
      EXPECT_NEAR(r.result.cost, s.result.cost, 1e-9 * s.result.cost);
    }
    expect_valid_path(r, p);
  }
}

// A path that leaves a slab and comes back: start and goal lie in the top layer of the first
// slab, and the path (found among random fields) climbs into the second slab between them,
// so the walk back crosses the face twice.
TEST(DenseSlabs, APathThatCrossesASlabFaceAndComesBack) {
  if (g_comm->size() < 2) GTEST_SKIP() << "needs two slabs";
  GridProblem found;
  bool have = false;
  for (std::uint64_t seed = 1; seed < 400 && !have; ++seed) {
    GridProblem p;
    p.dims = 3;
    p.extent = 24;
    p.gog.seed = seed;
    p.gog.density = 0.3 + 0.05 * static_cast<double>(seed % 6);
    const GogField field(3, 24, p.gog);
    const dense::TileLayout layout(3, 24, 2);
    const int face =
        dense::balanced_slabs(dense::free_states_per_layer(field, layout), g_comm->size())[1];
    if (face < 1) continue;
    std::vector<int> a{0, 0, face - 1}, b{23, 23, face - 1};
    while (a[0] < 23 && !field.is_free(a)) ++a[0];
    while (b[0] > 0 && !field.is_free(b)) --b[0];
    if (!field.is_free(a) || !field.is_free(b)) continue;
    p.start = a;
    p.goal = b;
    GridSearchOptions o;
    o.algorithm = GridAlgorithm::bfs;
    o.engine = GridEngine::dense;
    o.keep_path = true;
    o.threads = 1;
    const GridReport s = solve_grid(p, o);
    if (s.result.status != search::Status::solved) continue;
    bool above = false;
    for (const auto& c : s.result.path) above = above || c[2] >= face;
    if (above) {
      found = p;
      have = true;
    }
  }
  ASSERT_TRUE(have);
  for (const char* algo : {"bfs", "dijkstra"}) {
    GridSearchOptions o;
    o.algorithm = parse_grid_algorithm(algo);
    o.engine = GridEngine::dense;
    o.keep_path = true;
    o.threads = 1;
    const GridReport r = distributed::solve_grid_distributed(found, o, {}, *g_comm);
    if (!root()) continue;
    const GridReport s = solve_grid(found, o);
    EXPECT_EQ(r.result.path, s.result.path) << algo;
    EXPECT_EQ(r.result.cost, s.result.cost) << algo;
    expect_valid_path(r, found);
  }
}

// Each rank allocates its slab, not the lattice: the figure falls as about 1/P of the serial
// one (the window table and a layer's lists are per rank whatever P).
TEST(DenseSlabs, BytesPerRankAreAboutAShareOfTheSerialFigure) {
  GridProblem p;
  p.dims = 3;
  p.extent = 200;  // 200 layers: slabs of nearly equal width for any P here
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::bfs;
  o.engine = GridEngine::dense;
  o.threads = 1;
  const GridReport r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
  if (!root()) return;
  const GridReport s = solve_grid(p, o);
  ASSERT_TRUE(r.dense && s.dense);
  const double P = g_comm->size();
  const double table = static_cast<double>(s.dense->table_bytes);
  EXPECT_EQ(r.dense->table_bytes, s.dense->table_bytes);
  const double serial = static_cast<double>(s.dense->bytes_per_rank) - table;
  const double share = static_cast<double>(r.dense->bytes_per_rank) - table;
  // The slabs balance free states, not layers: the widest slab may hold a few more layers
  // (and its frontier lists a few more entries).
  EXPECT_LE(share, serial / P * 1.4 + 64e3) << "P = " << P << ", serial " << serial;
  if (P > 1) {
    EXPECT_LT(share, serial * 0.75) << "P = " << P;
  }
  EXPECT_GE(static_cast<double>(r.dense->bytes_total), share * P * 0.5);
}

// no_path, a stop and an over-budget refusal reach every rank alike.
// Checkpoints on every rank count: a run interrupted at its k-th boundary on every rank (one
// file per rank) and restarted, again and again until it ends, gives the uninterrupted
// answer, path and counts; a restart missing one rank's file is refused on every rank (no rank
// left waiting), with that rank's name in the message.
TEST(DenseSlabs, InterruptedAndRestartedRunsGiveTheUninterruptedAnswer) {
  // One folder for the job: rank 0's process id, known to all.
  const int pid = static_cast<int>(::getpid());
  const std::vector<std::byte> pids = g_comm->allgather(std::as_bytes(std::span(&pid, 1)));
  int root_pid = 0;
  std::memcpy(&root_pid, pids.data(), sizeof root_pid);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("hpcplan-mpi-ckpt-" + std::to_string(root_pid));
  if (root()) std::filesystem::create_directories(dir);
  g_comm->quiet_barrier();
  SplitMix64 rng(77);
  int interrupted = 0;
  for (int d = 2; d <= 4; ++d) {
    GridProblem p;
    p.dims = d;
    p.extent = d == 2 ? 40 : d == 3 ? 16 : 10;
    p.gog.seed = rng.next();
    for (const char* algo : {"bfs", "dijkstra"})
      for (int threads : {1, 2}) {
        GridSearchOptions o;
        o.algorithm = parse_grid_algorithm(algo);
        o.engine = GridEngine::dense;
        o.keep_path = true;
        o.threads = threads;
        const GridReport whole = distributed::solve_grid_distributed(p, o, {}, *g_comm);
        SCOPED_TRACE(::testing::Message() << "d=" << d << " " << algo << " threads=" << threads
                                          << " ranks=" << g_comm->size());
        GridReport r;
        for (int leg = 0; leg < 1000; ++leg) {
          auto calls = std::make_shared<int>(0);
          o.interrupted = [calls] { return ++*calls == 5; };
          o.checkpoint = (dir / (leg % 2 ? "b" : "a")).string();
          o.restart = leg == 0 ? "" : (dir / (leg % 2 ? "a" : "b")).string();
          r = distributed::solve_grid_distributed(p, o, {}, *g_comm);
          if (r.result.status != search::Status::interrupted) break;
          ++interrupted;
        }
        EXPECT_EQ(r.result.status, whole.result.status);
        EXPECT_EQ(r.result.cost, whole.result.cost);
        EXPECT_EQ(r.result.hops, whole.result.hops);
        EXPECT_EQ(r.result.path, whole.result.path);
        EXPECT_EQ(r.result.counters.expanded, whole.result.counters.expanded);
        EXPECT_EQ(r.result.counters.generated, whole.result.counters.generated);
        EXPECT_EQ(r.result.counters.peak_open, whole.result.counters.peak_open);
        EXPECT_EQ(r.dense->levels, whole.dense->levels);
      }
  }
  EXPECT_GT(interrupted, 20);
  // Rank (P - 1)'s file of the last interrupted leg is gone: every rank refuses.
  if (g_comm->size() > 1) {
    GridProblem p;
    p.dims = 3;
    p.extent = 20;
    GridSearchOptions o;
    o.algorithm = GridAlgorithm::bfs;
    o.engine = GridEngine::dense;
    o.threads = 1;
    o.interrupted = [] { return true; };
    o.checkpoint = (dir / "c").string();
    ASSERT_EQ(distributed::solve_grid_distributed(p, o, {}, *g_comm).result.status,
              search::Status::interrupted);
    g_comm->quiet_barrier();
    const std::string last = dense::rank_file(o.checkpoint, g_comm->size() - 1, g_comm->size());
    if (root()) std::filesystem::remove(last);
    g_comm->quiet_barrier();
    o.checkpoint.clear();
    o.interrupted = nullptr;
    o.restart = (dir / "c").string();
    try {
      distributed::solve_grid_distributed(p, o, {}, *g_comm);
      ADD_FAILURE() << "a restart missing a rank's file was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "rank " + std::to_string(g_comm->size() - 1) +
                                           ": --restart '" + last +
                                           "': is not a readable regular file");
    }
  }
  // A job stopped while its ranks were writing: rank P-1's file is from the boundary before
  // the others'. Every rank refuses the mixed set.
  if (g_comm->size() > 1) {
    GridProblem p;
    p.dims = 3;
    p.extent = 20;
    GridSearchOptions o;
    o.algorithm = GridAlgorithm::dijkstra;
    o.engine = GridEngine::dense;
    o.threads = 1;
    o.checkpoint = (dir / "d").string();
    const std::string last = dense::rank_file(o.checkpoint, g_comm->size() - 1, g_comm->size());
    for (int at : {2, 3}) {
      auto calls = std::make_shared<int>(0);
      o.interrupted = [calls, at] { return ++*calls == at; };
      ASSERT_EQ(distributed::solve_grid_distributed(p, o, {}, *g_comm).result.status,
                search::Status::interrupted);
      g_comm->quiet_barrier();
      if (root() && at == 2) std::filesystem::copy_file(last, last + ".older");
      g_comm->quiet_barrier();
    }
    if (root()) std::filesystem::rename(last + ".older", last);
    g_comm->quiet_barrier();
    o.restart = o.checkpoint;
    o.checkpoint.clear();
    o.interrupted = nullptr;
    try {
      distributed::solve_grid_distributed(p, o, {}, *g_comm);
      ADD_FAILURE() << "checkpoints of two boundaries were accepted together";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("written at different boundaries (2 and 3)"),
                std::string::npos)
          << e.what();
    }
  }
  g_comm->quiet_barrier();
  if (root()) std::filesystem::remove_all(dir);
}

TEST(DenseSlabs, NoPathTimeoutAndBudgetAreAgreedByEveryRank) {
  const GridProblem wall = walled_line();
  for (const char* algo : {"bfs", "dijkstra"}) {
    GridSearchOptions o;
    o.algorithm = parse_grid_algorithm(algo);
    o.engine = GridEngine::dense;
    o.threads = 1;
    EXPECT_EQ(distributed::solve_grid_distributed(wall, o, {}, *g_comm).result.status,
              search::Status::no_path)
        << algo;
    GridProblem big;
    big.dims = 6;
    big.extent = 30;
    o.time_limit_s = 1e-9;  // a limit no machine meets
    EXPECT_EQ(distributed::solve_grid_distributed(big, o, {}, *g_comm).result.status,
              search::Status::timeout)
        << algo;
    o.time_limit_s = 0;
    o.memory_budget = 100'000;
    EXPECT_THROW(distributed::solve_grid_distributed(big, o, {}, *g_comm), InputError) << algo;
  }
}

TEST(Ownership, SpreadsStatesEvenlyAndCoarseningKeepsCellsTogether) {
  const KeyLayout layout(3, 64);
  const partition::Ownership<1> fine(layout, 4, 0), coarse(layout, 4, 2);
  std::map<int, int> counts;
  int same_cell_same_owner = 0, cells_checked = 0;
  for (int x = 0; x < 64; ++x)
    for (int y = 0; y < 64; ++y)
      for (int z = 0; z < 64; ++z) {
        const int c[3] = {x, y, z};
        const auto key = layout.pack<1>(c);
        ++counts[fine(key)];
        const int base[3] = {x & ~3, y & ~3, z & ~3};
        ++cells_checked;
        same_cell_same_owner += coarse(key) == coarse(layout.pack<1>(base));
      }
  ASSERT_EQ(counts.size(), 4u);
  for (const auto& [owner, n] : counts) EXPECT_NEAR(n, 65536, 65536 * 0.02) << owner;
  EXPECT_EQ(same_cell_same_owner, cells_checked);
  const partition::Ownership<1> one(layout, 1, 0);
  EXPECT_EQ(one(layout.pack<1>(std::vector<int>{5, 6, 7})), 0);
  // One rank owns every neighbourhood; the hash vouches for none (it is asked per successor).
  EXPECT_TRUE(one.holds_neighbourhood(layout.pack<1>(std::vector<int>{5, 6, 7})));
  EXPECT_FALSE(partition::Ownership<1>(layout, 2, 2)
                   .holds_neighbourhood(layout.pack<1>(std::vector<int>{5, 6, 7})));
}

// Slabs: the owner depends on the last coordinate alone, (x / w) mod P, on every key width.
template <int W>
void expect_slab_owners(int dims, int extent) {
  const KeyLayout layout(dims, extent);
  ASSERT_EQ(layout.words(), W);
  SplitMix64 rng(7);
  for (const int ranks : {2, 3, 8})
    for (const int width : {1, 3, extent}) {
      const partition::Ownership<W> slabs(layout, ranks, 0, width, extent);
      EXPECT_EQ(slabs.slab_width(), width);
      int interior = 0;
      for (int i = 0; i < 2000; ++i) {
        std::vector<int> c(dims);
        for (int& x : c) x = static_cast<int>(rng.next_below(extent));
        const auto s = layout.pack<W>(c);
        const int x = c[dims - 1];
        const int owner = (x / width) % ranks;
        ASSERT_EQ(slabs(s), owner) << "dims " << dims << " ranks " << ranks << " width " << width;
        // A state that vouches for its neighbourhood: every state one step away on any axes
        // (the last axis decides; both steps, clamped to the lattice) has its owner.
        if (!slabs.holds_neighbourhood(s)) continue;
        ++interior;
        for (const int step : {-1, 1}) {
          std::vector<int> t = c;
          t[dims - 1] = std::clamp(x + step, 0, extent - 1);
          if (dims > 1) t[0] = std::clamp(c[0] - step, 0, extent - 1);
          ASSERT_EQ(slabs(layout.pack<W>(t)), owner)
              << "dims " << dims << " ranks " << ranks << " width " << width << " x " << x;
        }
      }
      // Interior last coordinates: those whose two neighbours share their slab's owner.
      int expected_interior = 0;
      for (int x = 0; x < extent; ++x) {
        const int o = (x / width) % ranks;
        expected_interior += (x == 0 || ((x - 1) / width) % ranks == o) &&
                             (x == extent - 1 || ((x + 1) / width) % ranks == o);
      }
      if (expected_interior == 0)
        EXPECT_EQ(interior, 0) << "dims " << dims << " ranks " << ranks << " width " << width;
      else if (expected_interior == extent)
        EXPECT_EQ(interior, 2000) << "dims " << dims << " ranks " << ranks << " width " << width;
      else
        EXPECT_GT(interior, 0) << "dims " << dims << " ranks " << ranks << " width " << width;
    }
}

TEST(Ownership, SlabsFollowTheLastCoordinate) {
  expect_slab_owners<1>(6, 11);
  expect_slab_owners<2>(10, 1000);  // 10 bits per axis: two words
  // A coarsening shift given with slabs is ignored, not mixed in.
  const KeyLayout layout(3, 16);
  EXPECT_EQ(partition::Ownership<1>(layout, 2, 2, 4, 16).coarsen_shift(), 0);
}

// Cuts placed on a serial run's expansions split the real run's expansions about evenly, for
// the job's rank count.
TEST(Distributed, BalancedPrefixCutsSplitTheWorkEvenly) {
  const int p_ranks = g_comm->size();
  if (p_ranks == 1) {
    GTEST_SKIP() << "one rank has nothing to balance";
  }
  GridProblem p;
  p.dims = 4;
  p.extent = 16;
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::dijkstra;
  o.engine = GridEngine::sparse;  // the best-first engine\'s schedules
  const partition::RankSimulation sim = partition::simulate_ranks(p, o, {p_ranks}, {0});
  distributed::DistGridOptions d;
  d.scheme = distributed::Scheme::bulk_sync;
  d.prefix_cuts = partition::balanced_prefix_cuts(sim, p_ranks);
  ASSERT_EQ(d.prefix_cuts.size(), static_cast<std::size_t>(p_ranks - 1));
  const GridReport r = distributed::solve_grid_distributed(p, o, d, *g_comm);
  // Two contiguous slabs of the same lattice (collective: every rank runs it).
  distributed::DistGridOptions halves;
  halves.scheme = distributed::Scheme::bulk_sync;
  halves.slab_width = 8;
  const GridReport h = distributed::solve_grid_distributed(p, o, halves, *g_comm);
  if (!root()) return;
  ASSERT_EQ(r.result.status, search::Status::solved);
  EXPECT_NEAR(r.result.cost, sim.serial.result.cost, 1e-9 * (1 + r.result.cost));
  EXPECT_EQ(r.distribution.prefix_cuts, d.prefix_cuts);
  // One of 256 positions holds at most a few percent of the work, so a cut lands within it.
  const double deviation = workload_deviation_percent(r.distribution.per_rank);
  EXPECT_LT(deviation, 8.0) << "cuts at " << ::testing::PrintToString(d.prefix_cuts);
  // The halves are far less even at two ranks: the search starts in one of them.
  if (p_ranks == 2) {
    EXPECT_LT(deviation, workload_deviation_percent(h.distribution.per_rank));
  }
}

TEST(Ownership, PrefixCutsOwnByPositionAndVouchOnlyForInteriorStates) {
  const KeyLayout layout(3, 10);
  SplitMix64 rng(11);
  const std::vector<std::uint32_t> cuts{23, 24, 57};  // rank 1 owns position 23 alone
  const partition::Ownership<1> owner(layout, 4, 0, 0, 10, cuts);
  EXPECT_EQ(owner.slab_width(), 0);
  EXPECT_EQ(owner.prefix_cuts(), cuts);
  int interior = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<int> c(3);
    for (int& x : c) x = static_cast<int>(rng.next_below(10));
    const auto s = layout.pack<1>(c);
    // The last two axes, the last first.
    const auto position = static_cast<std::uint32_t>(c[2] * 10 + c[1]);
    const int expected =
        static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), position) - cuts.begin());
    ASSERT_EQ(owner(s), expected) << c[2] << "," << c[1];
    if (!owner.holds_neighbourhood(s)) continue;
    ++interior;
    for (int da = -1; da <= 1; ++da)
      for (int db = -1; db <= 1; ++db) {
        std::vector<int> t = c;
        t[2] = std::clamp(c[2] + da, 0, 9);
        t[1] = std::clamp(c[1] + db, 0, 9);
        t[0] = std::clamp(c[0] + da, 0, 9);
        ASSERT_EQ(owner(layout.pack<1>(t)), expected) << c[2] << "," << c[1];
      }
  }
  EXPECT_GT(interior, 1000);
  // Rank 1's single position has no interior state.
  EXPECT_FALSE(owner.holds_neighbourhood(layout.pack<1>(std::vector<int>{5, 3, 2})));
  // One position fewer than ranks, strictly ascending, inside the lattice.
  EXPECT_THROW(partition::Ownership<1>(layout, 3, 0, 0, 10, {5}), std::logic_error);
  EXPECT_THROW(partition::Ownership<1>(layout, 3, 0, 0, 10, {5, 5}), std::logic_error);
  EXPECT_THROW(partition::Ownership<1>(layout, 2, 0, 0, 10, {100}), std::logic_error);
  // A 2D lattice of 60,000^2 states: cuts keep nothing of that size (positions near 2^32).
  const KeyLayout wide(2, 60000);
  const partition::Ownership<1> halves(wide, 2, 0, 0, 60000, {1'800'000'000u});
  EXPECT_EQ(halves(wide.pack<1>(std::vector<int>{59999, 29999})), 0);
  EXPECT_EQ(halves(wide.pack<1>(std::vector<int>{0, 30000})), 1);
  EXPECT_EQ(halves(wide.pack<1>(std::vector<int>{59999, 59999})), 1);
  EXPECT_FALSE(halves.holds_neighbourhood(wide.pack<1>(std::vector<int>{59999, 29999})));
  EXPECT_TRUE(halves.holds_neighbourhood(wide.pack<1>(std::vector<int>{59999, 59999})));
}

TEST(Ownership, BalancedPrefixCutsFollowTheHistogram) {
  partition::RankSimulation sim;
  sim.expanded_by_prefix = {1, 1, 1, 1};
  EXPECT_EQ(partition::balanced_prefix_cuts(sim, 2), (std::vector<std::uint32_t>{2}));
  EXPECT_EQ(partition::balanced_prefix_cuts(sim, 4), (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_TRUE(partition::balanced_prefix_cuts(sim, 1).empty());
  EXPECT_THROW(partition::balanced_prefix_cuts(sim, 5), InputError);
  // A lattice too large for the census has no histogram, and says so.
  partition::RankSimulation huge;
  EXPECT_THROW(partition::balanced_prefix_cuts(huge, 2), InputError);
  // One heavy position still leaves every rank a position of its own.
  sim.expanded_by_prefix = {0, 100, 0, 0};
  EXPECT_EQ(partition::balanced_prefix_cuts(sim, 3), (std::vector<std::uint32_t>{1, 2}));
  // The cut goes to the nearer side of the position that crosses the share (half is 50).
  sim.expanded_by_prefix = {10, 10, 70, 10};  // 20 | 80 rather than 90 | 10
  EXPECT_EQ(partition::balanced_prefix_cuts(sim, 2), (std::vector<std::uint32_t>{2}));
  sim.expanded_by_prefix = {30, 10, 15, 45};  // 55 | 45 rather than 40 | 60
  EXPECT_EQ(partition::balanced_prefix_cuts(sim, 2), (std::vector<std::uint32_t>{3}));
}

TEST(DistributedOptions, ImpossibleValuesAreInputErrors) {
  distributed::DistGridOptions d;
  d.batch = 0;
  EXPECT_THROW(distributed::validate(d), InputError);
  d = {};
  d.coarsen_shift = 40;
  EXPECT_THROW(distributed::validate(d), InputError);
  d = {};
  d.sync_every = 0;
  EXPECT_THROW(distributed::validate(d), InputError);
  d = {};
  d.slab_width = -1;
  EXPECT_THROW(distributed::validate(d), InputError);
  d.slab_width = 2;
  d.coarsen_shift = 1;  // two ownerships at once
  EXPECT_THROW(distributed::validate(d), InputError);
  d.coarsen_shift = 0;
  EXPECT_NO_THROW(distributed::validate(d));
  // Wider than the lattice: refused before any rank starts searching.
  GridProblem p;
  p.dims = 2;
  p.extent = 8;
  d.slab_width = 9;
  EXPECT_THROW(distributed::solve_grid_distributed(p, GridSearchOptions{}, d, *g_comm), InputError);
  // Prefix cuts: one fewer than ranks, ascending, inside extent^2, and not with another owner.
  d = {};
  d.prefix_cuts = {64};
  EXPECT_THROW(distributed::validate(d, 8, 2, 2), InputError);
  d.prefix_cuts = {0};
  EXPECT_THROW(distributed::validate(d, 8, 2, 2), InputError);
  d.prefix_cuts = {10, 10};
  EXPECT_THROW(distributed::validate(d, 8, 3, 2), InputError);
  d.prefix_cuts = {10};
  EXPECT_THROW(distributed::validate(d, 8, 3, 2), InputError);
  EXPECT_NO_THROW(distributed::validate(d, 8, 2, 2));
  d.slab_width = 2;
  EXPECT_THROW(distributed::validate(d, 8, 2, 2), InputError);
  EXPECT_THROW(distributed::parse_scheme("sometimes"), InputError);
}

}  // namespace

int main(int argc, char** argv) {
  hpcplan::mpi::Session session(argc, argv);
  const hpcplan::mpi::Communicator comm;
  g_comm = &comm;
  ::testing::InitGoogleTest(&argc, argv);
  // The launcher must have given this process the ranks ctest asked for: an mpirun that does not
  // match the MPI library starts N independent one-rank jobs, which would pass every test.
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]).starts_with("--expect-ranks=")) {
      const int expected = std::stoi(argv[i] + 15);
      if (comm.size() != expected) {
        std::fprintf(stderr, "rank %d: the communicator has %d ranks, %d were launched\n",
                     comm.rank(), comm.size(), expected);
        return 1;
      }
    }
  // Only rank 0 prints test progress; every rank's failures still set its exit code.
  if (comm.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failed = RUN_ALL_TESTS();
  return failed;
}
