// The one OMPL world adapter on the GOG field (against the lattice and the world's walk), the grid
// planner inside OMPL, and the benchmark harness's bookkeeping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/gog_world.hpp"
#include "hpcplan/io/ompl_bench_csv.hpp"
#include "hpcplan/plan/grid_astar_planner.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/plan/ompl_benchmark.hpp"
#include "hpcplan/sampling/gog_space.hpp"
#include "hpcplan/sampling/path_tightening.hpp"
#include "hpcplan/sampling/world_ompl.hpp"
#include "support/shortest_path_2d.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::sampling {
namespace {

// The grid planner as an OMPL planner and the benchmark harness live one layer up, in plan.
using plan::fmt_samples;
using plan::GridAStarPlanner;
using plan::OmplBenchOptions;
using plan::run_ompl_benchmark;

GogSpace space_for(int dims, int extent, double resolution = 0.1, std::uint64_t seed = 1) {
  GogParams p;
  p.seed = seed;
  return make_gog_space(std::make_shared<const GogField>(dims, extent, p), resolution);
}

std::vector<double> coords(const ob::ScopedState<>& s, int d) {
  std::vector<double> x(d);
  for (int a = 0; a < d; ++a) x[a] = s[a];
  return x;
}

// The adapter's validity checker is the world's point test, counted on the world's counter,
// for every dimension the runtime dispatch picks.
class CheckerAgreement : public ::testing::TestWithParam<int> {};

TEST_P(CheckerAgreement, RandomPointsMatchTheLatticeAndAreCounted) {
  const int d = GetParam();
  const int extent = 40;
  const GogSpace w = space_for(d, extent);
  EXPECT_EQ(w.si->getStateDimension(), static_cast<unsigned>(d));
  std::mt19937_64 rng(1234 + d);
  std::uniform_real_distribution<double> u(0.0, extent);
  ob::ScopedState<> s(w.space);
  const std::uint64_t before = w.checks->value();
  int free = 0;
  for (int i = 0; i < 5000; ++i) {
    std::vector<int> cell(d);
    for (int a = 0; a < d; ++a) {
      const double x = i % 5 == 0 ? std::floor(u(rng) + 0.5) : u(rng);  // some on faces
      s[a] = x;
      cell[a] = std::min(static_cast<int>(std::floor(x)), extent - 1);
    }
    const bool native = w.field->is_free(cell);
    ASSERT_EQ(w.si->isValid(s.get()), native) << "point " << i;
    free += native;
  }
  EXPECT_EQ(w.checks->value() - before, 5000u);
  EXPECT_GT(free, 250);  // both outcomes exercised
  EXPECT_LT(free, 4750);
}

INSTANTIATE_TEST_SUITE_P(Dims, CheckerAgreement, ::testing::Values(2, 4, 7, 10));

TEST(GogSpace, PointsOutsideTheBoxAreInvalid) {
  const GogSpace w = space_for(2, 20);
  ob::ScopedState<> s(w.space);
  s[0] = -0.001;
  s[1] = 1.0;
  EXPECT_FALSE(w.si->isValid(s.get()));
  s[0] = 20.001;
  EXPECT_FALSE(w.si->isValid(s.get()));
  s[0] = std::nan("");
  EXPECT_FALSE(w.si->isValid(s.get()));
}

TEST(GogSpace, MotionValidatorRejectsASegmentThroughABlockedCell) {
  const GogSpace w = space_for(2, 100);
  // Find free - blocked - free along axis 0.
  const GogField& f = *w.field;
  for (int y = 0; y < 100; ++y)
    for (int x = 1; x + 1 < 100; ++x) {
      if (!f.is_free(std::vector<int>{x - 1, y}) || f.is_free(std::vector<int>{x, y}) ||
          !f.is_free(std::vector<int>{x + 1, y}))
        continue;
      ob::ScopedState<> a(w.space), b(w.space);
      cell_centre({x - 1, y}, a.get());
      cell_centre({x + 1, y}, b.get());
      EXPECT_FALSE(w.si->checkMotion(a.get(), b.get()));
      EXPECT_EQ(first_invalid_step(w, {coords(a, 2), coords(b, 2)}), 1);
      return;
    }
  FAIL() << "no free-blocked-free triple found";
}

// The exact motion validator is the world's voxel walk (env/gog_world.hpp, tested against
// dense sampling there): same verdicts, its cells counted, and a last valid state that is
// valid and just short of the first contact.
class ExactMotion : public ::testing::TestWithParam<int> {};

TEST_P(ExactMotion, IsTheWorldsWalkWithAValidLastState) {
  const int d = GetParam();
  const int extent = 24;
  const GogSpace w = space_for(d, extent);
  std::mt19937_64 rng(99 + d);
  std::uniform_real_distribution<double> u(0.0, extent);
  ob::ScopedState<> a(w.space), b(w.space), last(w.space);
  int rejected = 0;
  for (int n = 0; n < 2000; ++n) {
    for (int i = 0; i < d; ++i) {
      a[i] = u(rng);
      b[i] = std::clamp(a[i] + (u(rng) - extent / 2.0) / 3.0, 0.0, double(extent));
    }
    if (!w.si->isValid(a.get())) continue;
    const auto pa = coords(a, d), pb = coords(b, d);
    const env::GogSegmentWalk walk = env::gog_walk_segment(*w.field, pa.data(), pb.data());
    const std::uint64_t before = w.checks->value();
    ASSERT_EQ(w.si->checkMotion(a.get(), b.get()), walk.free) << "n=" << n;
    EXPECT_EQ(w.checks->value() - before, walk.cells);
    std::pair<ob::State*, double> last_valid(last.get(), -1.0);
    ASSERT_EQ(w.si->getMotionValidator()->checkMotion(a.get(), b.get(), last_valid), walk.free);
    if (walk.free) continue;
    ++rejected;
    EXPECT_LE(last_valid.second, walk.blocked_at);
    EXPECT_GT(last_valid.second, walk.blocked_at - 1e-3);
    EXPECT_TRUE(w.si->isValid(last.get())) << "n=" << n;
    EXPECT_TRUE(w.si->checkMotion(a.get(), last.get())) << "n=" << n;
  }
  EXPECT_GT(rejected, 50);
}

INSTANTIATE_TEST_SUITE_P(Dims, ExactMotion, ::testing::Values(2, 3, 5, 8));

// solve_with_ompl goes through the same adapter for any world: here the GOG field as a 3D
// world, the path checked segment by segment with the world's exact test and by sampling.
TEST(WorldSpace, OmplPlannersSolveTheGogWorldWithValidPaths) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  GogParams p;
  p.seed = 7;
  const auto field = std::make_shared<const GogField>(3, 30, p);
  const env::GogWorld<3> w(field);
  const auto s = adjust_to_free(*field, {0, 0, 0}, +1, "start");
  const auto g = adjust_to_free(*field, {29, 29, 29}, -1, "goal");
  const env::Vec<3> start{s[0] + 0.5, s[1] + 0.5, s[2] + 0.5};
  const env::Vec<3> goal{g[0] + 0.5, g[1] + 0.5, g[2] + 0.5};
  const auto r = solve_with_ompl(w, start, goal, "rrtconnect", 20.0, 5);
  ASSERT_EQ(r.status, Status::solved);
  EXPECT_EQ(r.path.front(), start);
  EXPECT_EQ(r.path.back(), goal);
  EXPECT_GT(r.counters.collision_checks, 0u);
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    ASSERT_TRUE(w.segment_free(r.path[i - 1], r.path[i])) << "segment " << i;
    for (int k = 0; k <= 100; ++k)
      ASSERT_TRUE(
          env::gog_point_free(*field, env::lerp<3>(r.path[i - 1], r.path[i], k / 100.0).data()));
  }
}

TEST(GogSpace, BadResolutionOrDimensionIsAnInputError) {
  auto f = std::make_shared<const GogField>(2, 10, GogParams{});
  EXPECT_THROW(make_gog_space(f, 0.0), InputError);
  EXPECT_THROW(make_gog_space(f, 1.5), InputError);
  EXPECT_THROW(make_gog_space(std::make_shared<const GogField>(17, 2, GogParams{}), 0.1),
               InputError);
}

// Solves the seed problem with the grid planner through OMPL and returns the path.
og::PathGeometric solve_with_grid(const GogSpace& w, bool shortcut, GridReport* report,
                                  double smoothing_budget = 1.0) {
  const int d = w.field->dims();
  const auto s = adjust_to_free(*w.field, std::vector<int>(d, 0), +1, "start");
  const auto g = adjust_to_free(*w.field, std::vector<int>(d, w.field->extent() - 1), -1, "goal");
  og::SimpleSetup ss(w.si);
  ob::ScopedState<> start(w.space), goal(w.space);
  cell_centre(s, start.get());
  cell_centre(g, goal.get());
  ss.setStartAndGoalStates(start, goal, 1e-6);
  ss.setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(w.si));
  auto planner = std::make_shared<GridAStarPlanner>(w);
  planner->setShortcut(shortcut);
  planner->setSmoothingBudget(smoothing_budget);
  ss.setPlanner(planner);
  // The grid planner is complete and bounded by its state budget: no deadline (a converged
  // smoothing, budget 0, would be cut short by one).
  const auto status = ss.solve(ob::plannerNonTerminatingCondition());
  EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  if (report) *report = planner->lastReport();
  return ss.getSolutionPath();
}

class GridPlannerInOmpl : public ::testing::TestWithParam<int> {};

TEST_P(GridPlannerInOmpl, LatticePathIsTheSearchCostAndShortcutsOnlyShorten) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const int d = GetParam();
  const GogSpace w = space_for(d, d <= 4 ? 60 : 12);
  GridReport report;
  og::PathGeometric lattice = solve_with_grid(w, false, &report);
  ASSERT_EQ(report.result.status, search::Status::solved);
  // Cell centres to cell centres: the continuous length is the lattice cost exactly.
  EXPECT_NEAR(lattice.length(), report.result.cost, 1e-9 * report.result.cost);
  EXPECT_TRUE(lattice.check());
  std::vector<std::vector<double>> pts;
  for (std::size_t i = 0; i < lattice.getStateCount(); ++i) {
    const double* x = lattice.getState(i)->as<ob::RealVectorStateSpace::StateType>()->values;
    pts.emplace_back(x, x + d);
  }
  EXPECT_EQ(first_invalid_step(w, pts), -1);

  og::PathGeometric shortened = solve_with_grid(w, true, nullptr);
  EXPECT_TRUE(shortened.check());
  EXPECT_LE(shortened.length(), lattice.length() + 1e-9);
  // Same ends, exactly.
  EXPECT_EQ(w.si->distance(shortened.getState(0), lattice.getState(0)), 0.0);
  EXPECT_EQ(w.si->distance(shortened.getState(shortened.getStateCount() - 1),
                           lattice.getState(lattice.getStateCount() - 1)),
            0.0);
}

INSTANTIATE_TEST_SUITE_P(Dims, GridPlannerInOmpl, ::testing::Values(2, 3, 4, 6));

// The tightener alone, on the lattice path: it reports what it did, never lengthens the path,
// keeps its ends, and leaves every motion valid under the world's (exact) validator.
TEST(PathTightening, ShortensALatticePathAndKeepsItValid) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const GogSpace w = space_for(4, 40);
  og::PathGeometric path = solve_with_grid(w, false, nullptr);
  const og::PathGeometric before = path;
  const auto stats = tighten_path(w.si, path, ob::plannerNonTerminatingCondition());
  EXPECT_GE(stats.rounds, 1);
  EXPECT_NEAR(stats.length_before, before.length(), 1e-9);
  EXPECT_NEAR(stats.length_after, path.length(), 1e-9);
  EXPECT_LT(stats.length_after, stats.length_before);  // 4D lattice paths have slack
  EXPECT_TRUE(path.check());
  EXPECT_EQ(w.si->distance(path.getState(0), before.getState(0)), 0.0);
  EXPECT_EQ(w.si->distance(path.getState(path.getStateCount() - 1),
                           before.getState(before.getStateCount() - 1)),
            0.0);
  for (std::size_t i = 1; i < path.getStateCount(); ++i)
    EXPECT_TRUE(w.si->checkMotion(path.getState(i - 1), path.getState(i))) << "segment " << i;
}

// The exact shortest path in a 2D GOG world (tests/support/shortest_path_2d.hpp).
double shortest_length_2d(const GogField& field, const env::Vec<2>& s, const env::Vec<2>& g,
                          double eps) {
  const env::GogWorld<2> world(std::make_shared<const GogField>(field));
  const int n = field.extent();
  const auto blocked = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < n && y < n && !field.is_free(std::vector<int>{x, y});
  };
  return test_support::shortest_length_2d(world, blocked, n, s, g, eps);
}

// The smoothing against that oracle, on fields of three seeds and two sizes: never shorter than
// the shortest path (it would have cut an obstacle). Run to convergence it is the taut path of
// the lattice path's class (env/taut_path_2d.hpp), which is the shortest overall on five of
// these six fields and 0.55% above it on the sixth (extent 100, seed 1), where the lattice
// path goes round an obstacle the other way; 1% allows for that and nothing more. On the
// default budget (the search's own time again) how far the passes get depends on the machine's
// speed, so that figure is a benchmark's (docs/PERFORMANCE.md), and this test asks only that
// the budgeted smoothing is valid and no longer than the lattice path it started from.
TEST(GridPlannerInOmpl, SmoothedPathIsNearTheExactShortestPathIn2D) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const auto point = [](const ob::State* st) {
    const double* x = st->as<ob::RealVectorStateSpace::StateType>()->values;
    return env::Vec<2>{x[0], x[1]};
  };
  for (const int extent : {40, 100})
    for (const std::uint64_t seed : {1, 2, 4}) {
      const GogSpace w = space_for(2, extent, 0.1, seed);
      const og::PathGeometric converged = solve_with_grid(w, true, nullptr, 0.0);
      const og::PathGeometric budgeted = solve_with_grid(w, true, nullptr, 1.0);
      const og::PathGeometric lattice = solve_with_grid(w, false, nullptr, 1.0);
      const double oracle =
          shortest_length_2d(*w.field, point(converged.getState(0)),
                             point(converged.getState(converged.getStateCount() - 1)), 1e-7);
      ASSERT_TRUE(std::isfinite(oracle));
      for (const og::PathGeometric* p : {&converged, &budgeted}) {
        EXPECT_TRUE(p->check());
        EXPECT_GE(p->length(), oracle - 1e-4);  // eps per corner at most
      }
      EXPECT_LE(converged.length(), 1.01 * oracle) << "extent " << extent << " seed " << seed;
      EXPECT_LE(budgeted.length(), lattice.length() + 1e-9)
          << "extent " << extent << " seed " << seed;
      EXPECT_LT(converged.length(), lattice.length()) << "extent " << extent << " seed " << seed;
      std::printf(
          "extent %d seed %d: shortest %.4f, smoothed +%.2f%% (converged) +%.2f%% "
          "(budget 1)\n",
          extent, static_cast<int>(seed), oracle, 100 * (converged.length() / oracle - 1),
          100 * (budgeted.length() / oracle - 1));
    }
}

TEST(GridPlannerInOmpl, DeclaresItsParametersToOmpl) {
  const GogSpace w = space_for(2, 20);
  GridAStarPlanner planner(w);
  auto& params = planner.params();
  for (const char* name : {"weight", "heuristic", "smoothing", "smoothing_budget", "time_limit"})
    EXPECT_TRUE(params.hasParam(name)) << name;
  EXPECT_TRUE(params.setParam("weight", "1.5"));
  EXPECT_DOUBLE_EQ(planner.getWeight(), 1.5);
  EXPECT_TRUE(params.setParam("heuristic", "euclidean"));
  EXPECT_EQ(planner.getHeuristic(), "euclidean");
  EXPECT_TRUE(params.setParam("smoothing", "0"));
  EXPECT_FALSE(planner.getShortcut());
  EXPECT_DOUBLE_EQ(planner.getSmoothingBudget(), 1.0);
  EXPECT_TRUE(params.setParam("smoothing_budget", "0"));
  EXPECT_DOUBLE_EQ(planner.getSmoothingBudget(), 0.0);
}

TEST(GridPlannerInOmpl, StartInsideAnObstacleIsReportedAsInvalidStart) {
  const GogSpace w = space_for(2, 100);
  std::vector<int> blocked;
  for (int x = 0; x < 100 && blocked.empty(); ++x)
    for (int y = 0; y < 100 && blocked.empty(); ++y)
      if (!w.field->is_free(std::vector<int>{x, y})) blocked = {x, y};
  ASSERT_FALSE(blocked.empty());
  og::SimpleSetup ss(w.si);
  ob::ScopedState<> start(w.space), goal(w.space);
  cell_centre(blocked, start.get());
  cell_centre(adjust_to_free(*w.field, {99, 99}, -1, "goal"), goal.get());
  ss.setStartAndGoalStates(start, goal, 1e-6);
  auto planner = std::make_shared<GridAStarPlanner>(w);
  ss.setPlanner(planner);
  ss.setup();
  // SimpleSetup drops invalid starts before the planner sees them; ask the planner directly.
  planner->getProblemDefinition()->clearStartStates();
  planner->getProblemDefinition()->addStartState(start);
  planner->clear();
  EXPECT_EQ(ss.getPlanner()->solve(1.0), ob::PlannerStatus::INVALID_START);
}

TEST(OmplBenchmark, FmtSamplesFollowSeedEquationOne) {
  EXPECT_EQ(fmt_samples(2), 2000u);
  EXPECT_EQ(fmt_samples(4), 8000u);
  EXPECT_EQ(fmt_samples(10), 98000u);
}

TEST(OmplBenchmark, BadOptionsAreInputErrors) {
  OmplBenchOptions o;
  o.planners = {"gridastar", "nosuchplanner"};
  EXPECT_THROW(validate(o), InputError);
  o = OmplBenchOptions{};
  o.planners = {"fmt", "fmt"};
  EXPECT_THROW(validate(o), InputError);
  o = OmplBenchOptions{};
  o.dims = 1;
  EXPECT_THROW(validate(o), InputError);
  o = OmplBenchOptions{};
  o.time_s = 0;
  EXPECT_THROW(validate(o), InputError);
  o = OmplBenchOptions{};
  o.runs = 0;
  EXPECT_THROW(validate(o), InputError);
  o = OmplBenchOptions{};
  o.planners.clear();
  EXPECT_THROW(validate(o), InputError);
}

// Two invocations, so that no outcome depends on the machine's speed: the planners that end
// at a path (the grid planners, RRT-Connect) under a 30 s guard they never reach, which must
// answer every run and smooth within it; and an anytime planner (BIT*) for 0.3 s, whose rows
// must be consistent whatever it managed in that time.
TEST(OmplBenchmark, EveryRunIsRecordedValidatedAndScored) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  OmplBenchOptions o;
  o.dims = 3;
  o.extent = 30;
  o.planners = {"gridastar", "gridastar_lattice", "rrtconnect"};
  o.time_s = 30.0;
  o.runs = 2;
  const auto r = run_ompl_benchmark(o);
  OmplBenchOptions oa = o;
  oa.planners = {"bitstar"};
  oa.time_s = 0.3;
  const auto anytime = run_ompl_benchmark(oa);
  ASSERT_EQ(r.rows.size(), 6u);
  ASSERT_EQ(anytime.rows.size(), 2u);
  ASSERT_GT(r.reference_quality, 0.0);
  auto check = [](const plan::OmplRunRow& row, double reference) {
    SCOPED_TRACE(row.planner + " run " + std::to_string(row.run));
    EXPECT_EQ(row.dims, 3);
    EXPECT_GT(row.collision_checks, 0u);
    if (!row.solved) return;
    EXPECT_TRUE(row.path_valid);  // re-checked by the harness for solved runs only
    // No path is shorter than the straight line (quality 1), whatever the planner.
    EXPECT_GE(row.quality_first, 1.0 - 1e-12);
    EXPECT_GE(row.quality_final, 1.0 - 1e-12);
    EXPECT_LE(row.quality_final, row.quality_first + 1e-12);
    // The improvements come in time order, each shorter than the one before.
    for (std::size_t k = 1; k < row.improvements.size(); ++k) {
      EXPECT_GE(row.improvements[k].first, row.improvements[k - 1].first);
      EXPECT_LE(row.improvements[k].second, row.improvements[k - 1].second + 1e-12);
    }
    if (!row.improvements.empty()) {
      EXPECT_EQ(row.time_first_s, row.improvements[0].first);
    }
    if (row.time_best_s >= 0) {
      EXPECT_TRUE(row.anytime);
      EXPECT_LE(row.quality_best, 0.5 * (row.quality_first + reference) + 1e-12);
    }
  };
  for (const auto& row : r.rows) {
    SCOPED_TRACE(row.planner + " run " + std::to_string(row.run));
    // Every planner here ends at a path, and this field is solvable: every run answers.
    EXPECT_TRUE(row.solved);
    if (row.planner.starts_with("gridastar")) {
      // It reports its answer through the intermediate-solution callback, as the anytime
      // planners do, so its first-solution time is taken the same way; one answer, no "best".
      EXPECT_EQ(row.improvements.size(), 1u);
      EXPECT_FALSE(row.anytime);
      EXPECT_LT(row.time_best_s, 0.0);
      // Its smoothing time is recorded (none without smoothing) and is part of its answer
      // time, so the lattice answer's time in the same run is t_first - smoothing.
      if (row.planner == "gridastar") {
        EXPECT_GT(row.smoothing_s, 0.0);
        EXPECT_LT(row.smoothing_s, row.time_first_s);
      } else {
        EXPECT_EQ(row.smoothing_s, 0.0);
      }
    } else {
      EXPECT_EQ(row.smoothing_s, -1.0);  // not a grid planner: not applicable
    }
    check(row, r.reference_quality);
  }
  for (const auto& row : anytime.rows) {
    EXPECT_EQ(row.smoothing_s, -1.0);
    check(row, anytime.reference_quality);
  }
  // The reference is the best final quality of a solved run.
  double best = 1e300;
  for (const auto& row : r.rows)
    if (row.solved) best = std::min(best, row.quality_final);
  EXPECT_DOUBLE_EQ(r.reference_quality, best);
  // The lattice path is the lattice optimum; the shortcut one is never longer.
  EXPECT_LE(r.rows[0].quality_final, r.rows[2].quality_final + 1e-12);
  const std::string csv = io::ompl_bench_csv(r);
  EXPECT_NE(r.ompl_log.find("GridAStar"), std::string::npos);
  EXPECT_EQ(csv.rfind("planner,dims,run,seed,solved,time_first_s,length_first,quality_first,"
                      "time_best_s,quality_best,quality_final,",
                      0),
            0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
}

}  // namespace
}  // namespace hpcplan::sampling
