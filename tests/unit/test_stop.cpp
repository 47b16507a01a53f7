// The stop condition every planning loop polls, and the thread contract of the worlds: a search
// cancelled from another thread ends promptly with consistent counters, and two planners may
// share one world while a third thread cancels one of them. This suite also runs under
// ThreadSanitizer (scripts/test.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stop_token>
#include <thread>
#include <vector>

#include "hpcplan/core/stop.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/graph/continuous_grid.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/sampling/ptc_stop.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/tree/rrt_star.hpp"
#include "support/cancel_handshake.hpp"
#include "support/path_checks.hpp"

namespace hpcplan {
namespace {

using Grid3 = ContinuousGrid<env::BoxWorld>;

TEST(Stop, DefaultNeverStopsAndReasonsAreReported) {
  Stop never;
  EXPECT_FALSE(never.can_stop());
  for (int i = 0; i < 1000; ++i) ASSERT_FALSE(never.poll());

  EXPECT_EQ(Stop::after(1e-9).check(), Status::timeout);
  EXPECT_FALSE(Stop::after(0).can_stop());  // 0 means no deadline
  EXPECT_FALSE(Stop::after(3600).check());

  std::stop_source source;
  Stop s = Stop::after(3600, source.get_token());
  EXPECT_FALSE(s.poll());
  source.request_stop();
  EXPECT_EQ(s.poll(), Status::cancelled);  // seen on the very next poll
  // Cancellation wins over an expired deadline.
  EXPECT_EQ(Stop::after(1e-9, source.get_token()).check(), Status::cancelled);
}

// A 6D Dijkstra over extent 40 would run for minutes; another thread cancels it. The search's
// own stop condition (polled every 64 polls) tells the canceller that the search is running and
// waits, on its third call, for the request: the token is read once per expansion, so the
// search must end at the next one. What is checked is a count of expansions, not how fast
// this machine (or a sanitizer) is.
TEST(Stop, AnotherThreadCancelsAGridSearchWithinOneExpansion) {
  GridProblem p;
  p.dims = 6;
  p.extent = 40;
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::dijkstra;
  o.engine = GridEngine::sparse;  // the best-first loop's poll (test_dense_engine.cpp: dense)
  o.max_states = 50'000'000;      // a guard: the test must never fill the machine
  test_support::CancelHandshake handshake;
  o.cancel = handshake.token();
  o.stop_when = handshake.condition(3);
  const std::jthread canceller = handshake.canceller();
  const GridReport r = solve_grid(p, o);
  ASSERT_EQ(r.result.status, Status::cancelled);
  EXPECT_EQ(handshake.calls(), 3);  // not polled again: the token ended it first
  EXPECT_TRUE(r.result.path.empty());
  // Three condition calls are 192 polls; one poll per expansion, and the next one stops it.
  EXPECT_GT(r.result.counters.expanded, 0u);
  EXPECT_LE(r.result.counters.expanded, 3u * 64u + 1u);
  // Counters of a search stopped between two expansions still add up.
  EXPECT_GE(r.result.counters.generated, r.result.counters.expanded);
  EXPECT_GE(r.result.counters.peak_states, r.result.counters.expanded);
  EXPECT_GE(r.result.counters.collision_checks, r.result.counters.generated);
}

// The dense visited store's pool and the radix open list's pool (IdlePool) lend to concurrent
// searches on several threads: Dijkstra and A* with the lattice heuristic both take a radix
// list. Four threads solving small lattices at once, eight times
// each, must each find exactly the serial answer; under ThreadSanitizer (label threads) this
// also checks the pool's hand-offs.
TEST(Stop, ConcurrentSearchesShareTheDenseStorePool) {
  GridProblem p;
  p.dims = 3;
  p.extent = 40;
  ASSERT_TRUE(dense_visited_fits(p.dims, p.extent));
  const GridReport reference = solve_grid(p, GridSearchOptions{});
  ASSERT_EQ(reference.result.status, Status::solved);
  std::atomic<int> wrong{0};
  {
    std::vector<std::jthread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (int k = 0; k < 8; ++k) {
          GridSearchOptions o;
          o.algorithm = (t + k) % 2 ? GridAlgorithm::astar : GridAlgorithm::dijkstra;
          const GridReport r = solve_grid(p, o);
          if (r.result.status != Status::solved || r.result.cost != reference.result.cost) ++wrong;
        }
      });
  }
  EXPECT_EQ(wrong.load(), 0);
}

// OMPL's termination condition, evaluated by the polling loop itself: check() sees it at once,
// poll() within 64 calls; a condition that stays false never stops the run.
TEST(Stop, OmplTerminationConditionStopsTheRun) {
  std::atomic<bool> done{false};
  int evaluated = 0;
  const ompl::base::PlannerTerminationCondition ptc([&] {
    ++evaluated;
    return done.load();
  });
  Stop stop = sampling::stop_on(ptc);
  EXPECT_TRUE(stop.can_stop());
  EXPECT_FALSE(stop.check());
  for (int i = 0; i < 1000; ++i) ASSERT_FALSE(stop.poll());
  EXPECT_GE(evaluated, 1000 / 64);
  EXPECT_LE(evaluated, 1000 / 64 + 1);  // not on every poll: the loop's cheap path stays cheap
  done = true;
  EXPECT_EQ(stop.check(), Status::cancelled);
  int polls = 1;
  while (!stop.poll()) ++polls;
  EXPECT_LE(polls, 64);
}

// The grid planner under OMPL: a condition that is already true ends the search at once
// (cancelled, nothing expanded beyond the first poll window); a false one lets it solve.
TEST(Stop, GridSearchEndsOnItsStopCondition) {
  GridProblem p;
  p.dims = 2;
  GridSearchOptions o;
  o.stop_when = [] { return true; };
  const GridReport stopped = solve_grid(p, o);
  EXPECT_EQ(stopped.result.status, Status::cancelled);
  EXPECT_LE(stopped.result.counters.expanded, 64u);
  o.stop_when = [] { return false; };
  EXPECT_EQ(solve_grid(p, o).result.status, Status::solved);
}

TEST(Stop, TwoPlannersShareOneWorldWhileAThirdCancels) {
  const auto map = env::load_box_map(std::string(HPCPLAN_MAPS_DIR) + "/maze.txt");
  const env::BoxWorld& w = map.world;

  // The reference, alone.
  const auto astar = [&](double resolution, Stop stop) {
    const Grid3 g(w, *map.start, *map.goal, {resolution});
    search::Options o;
    if (g.vertex_count() <= (std::uint64_t{1} << 26)) o.dense_keys = g.vertex_count();
    o.stop = stop;
    auto r = search::best_first_search<search::DenseThenHashPolicy>(g, Grid3::kStart, Grid3::kGoal,
                                                                    LatticeToGoal<Grid3>{&g}, o);
    std::vector<env::Vec<3>> path;
    for (auto s : r.path) path.push_back(g.point(s));
    return std::pair{r, path};
  };
  const auto alone = astar(0.25, {});
  ASSERT_EQ(alone.first.status, Status::solved);

  std::stop_source cancel_rrt, cancel_fine;
  std::atomic<int> finished{0};
  // Each cancelled planner says through its stop condition (polled every 64 polls) that it is
  // under way; the fine search then waits for its cancel, so it is cancelled mid-search on any
  // machine, and RRT* has drawn samples before it is cancelled.
  std::atomic<bool> rrt_running{false}, fine_running{false};
  decltype(astar(0.25, {})) together;
  tree::TreeResult<3> rrt;
  decltype(astar(0.25, {})) fine;
  {
    std::jthread a([&] {
      together = astar(0.25, {});
      ++finished;
    });
    std::jthread b([&] {
      tree::TreeOptions o;
      o.stop = Stop(cancel_rrt.get_token());  // nothing else ends RRT*: only the cancel
      o.stop.also_when([&] {
        rrt_running = true;
        return false;
      });
      rrt = tree::rrt_star(w, *map.start, *map.goal, o);
    });
    std::jthread c([&] {  // a 5 cm grid search, held open until it is cancelled
      Stop stop(cancel_fine.get_token());
      stop.also_when([&] {
        fine_running = true;
        while (!cancel_fine.stop_requested()) std::this_thread::yield();
        return false;
      });
      fine = astar(0.05, stop);
    });
    std::jthread canceller([&] {
      while (finished.load() == 0 || !rrt_running || !fine_running) std::this_thread::yield();
      cancel_rrt.request_stop();
      cancel_fine.request_stop();
    });
  }
  // The shared world gave the concurrent A* the same answer, with its own check count.
  ASSERT_EQ(together.first.status, Status::solved);
  EXPECT_EQ(together.first.cost, alone.first.cost);
  EXPECT_EQ(together.first.counters.expanded, alone.first.counters.expanded);
  EXPECT_EQ(together.first.counters.collision_checks, alone.first.counters.collision_checks);
  test_support::expect_valid(w, together.second, *map.start, *map.goal, "concurrent astar");
  // RRT* ran until cancelled (it had polled 64 times before it said so); whatever it holds
  // then is a valid path.
  EXPECT_GT(rrt.counters.samples, 0u);
  if (rrt.status == Status::solved)
    test_support::expect_valid(w, rrt.path, *map.start, *map.goal, "cancelled rrtstar");
  else
    EXPECT_EQ(rrt.status, Status::cancelled);
  EXPECT_EQ(fine.first.status, Status::cancelled);
  EXPECT_TRUE(fine.first.path.empty());
}

}  // namespace
}  // namespace hpcplan
