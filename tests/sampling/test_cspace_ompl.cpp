// Configuration spaces through OMPL (sampling/cspace_ompl.hpp): the metric and interpolation are
// Motion's, the batch motion validator answers as a scalar sample-by-sample check does, OMPL's
// planners solve the chain and the hypercube with paths that re-check valid, the c-space grid
// planner inside OMPL returns solve_grid's cost, and the harness's c-space worlds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/benchmark_spaces.hpp"
#include "hpcplan/plan/cspace_grid_planner.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/ompl_benchmark.hpp"
#include "hpcplan/sampling/cspace_ompl.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::sampling {
namespace {

using State = std::vector<double>;

void set(ob::ScopedState<>& s, const State& q) {
  for (std::size_t a = 0; a < q.size(); ++a) s[a] = q[a];
}

State values(const ob::State* s, int dims) {
  const double* x = s->as<ob::RealVectorStateSpace::StateType>()->values;
  return {x, x + dims};
}

// The scalar reference: the motion's samples one at a time; the index of the first invalid
// one, or -1.
long scalar_first_invalid(const ConfigSpace& space, const State& a, const State& b,
                          std::size_t& m) {
  std::vector<double> samples;
  m = Motion(space, a, b).samples(samples);
  for (std::size_t i = 0; i < m; ++i)
    if (!space.is_valid(samples.data() + i * space.dims())) return static_cast<long>(i);
  return -1;
}

TEST(CSpaceOmpl, DistanceAndInterpolationAreMotionsAcrossTheWrap) {
  const auto chain = make_benchmark_space("chain", 6).space;
  const CSpaceOmpl s = make_cspace_ompl(chain);
  const double pi = std::numbers::pi;
  // Axis 0 crosses +-pi the short way (0.2 rad, not 2 pi - 0.2); axis 1 does not wrap.
  const State a = {pi - 0.1, -1.0, 0.0, 0.5, -pi, 2.0};
  const State b = {-pi + 0.1, 1.0, 0.3, 0.5, pi - 1e-3, -2.0};
  ob::ScopedState<> sa(s.state_space), sb(s.state_space), out(s.state_space);
  set(sa, a);
  set(sb, b);
  const Motion motion(*chain, a, b);
  EXPECT_EQ(s.si->distance(sa.get(), sb.get()), motion.length());
  EXPECT_NEAR(motion.length(),
              std::sqrt(0.2 * 0.2 + 4.0 + 0.09 + 0.0 + 1e-6 + std::pow(2 * pi - 4.0, 2)), 1e-12);
  EXPECT_LE(s.state_space->getMaximumExtent(), std::sqrt(6.0) * pi + 1e-12);

  std::vector<double> samples;
  const std::size_t m = motion.samples(samples);
  ASSERT_GT(m, 10u);
  for (std::size_t i = 1; i <= m; ++i) {
    s.state_space->interpolate(sa.get(), sb.get(), static_cast<double>(i) / static_cast<double>(m),
                               out.get());
    const State q = values(out.get(), 6);
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(q[k], samples[(i - 1) * 6 + k]) << "sample " << i << " axis " << k;
      EXPECT_GE(q[k], -pi);
      EXPECT_LT(q[k], pi);
    }
  }
  // Half way along axis 0 is the wrap itself: -pi (the lower bound), never +pi.
  s.state_space->interpolate(sa.get(), sb.get(), 0.5, out.get());
  EXPECT_NEAR(std::abs(out[0]), pi, 1e-12);
  EXPECT_TRUE(s.state_space->satisfiesBounds(out.get()));

  // Wrapping: pi and -pi are one state; enforceBounds maps 3 pi / 2 to -pi / 2 and leaves states
  // inside the bounds untouched, bit for bit.
  ob::ScopedState<> p(s.state_space), q(s.state_space);
  set(p, {pi, 0, 0, 0, 0, 0});
  set(q, {-pi, 0, 0, 0, 0, 0});
  EXPECT_TRUE(s.state_space->equalStates(p.get(), q.get()));
  EXPECT_EQ(s.si->distance(p.get(), q.get()), 0.0);
  EXPECT_FALSE(s.state_space->satisfiesBounds(p.get()));
  set(p, {1.5 * pi, 0.1, 0, 0, 0, 0});
  s.state_space->enforceBounds(p.get());
  EXPECT_NEAR(p[0], -0.5 * pi, 1e-12);
  EXPECT_EQ(p[1], 0.1);
  set(p, a);
  s.state_space->enforceBounds(p.get());
  EXPECT_EQ(values(p.get(), 6), a);

  // The si's resolution is the space's step over the metric's extent.
  EXPECT_NEAR(s.si->getStateValidityCheckingResolution() * s.state_space->getMaximumExtent(),
              chain->resolution(), 1e-12);
}

TEST(CSpaceOmpl, HypercubeBoundsClampAndLeaveTheSpaceUnwrapped) {
  const auto cube = make_benchmark_space("hypercube", 4).space;
  const CSpaceOmpl s = make_cspace_ompl(cube);
  EXPECT_NEAR(s.state_space->getMaximumExtent(), 2.0, 1e-12);  // sqrt(4) x 1
  ob::ScopedState<> p(s.state_space), q(s.state_space);
  set(p, {-0.5, 1.5, 0.2, 1.0});
  EXPECT_FALSE(s.state_space->satisfiesBounds(p.get()));
  EXPECT_FALSE(s.si->isValid(p.get()));  // out of the bounds: invalid whatever the corridor says
  s.state_space->enforceBounds(p.get());
  EXPECT_EQ(values(p.get(), 4), (State{0.0, 1.0, 0.2, 1.0}));
  set(p, {0, 0, 0, 0});
  set(q, {1, 1, 1, 1});
  EXPECT_DOUBLE_EQ(s.si->distance(p.get(), q.get()), 2.0);
}

// Random motions, half of them short (where a motion of a few samples must agree too): the
// validator's answer, its last valid state and fraction, and the checks it counts.
class MotionAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(MotionAgreement, BatchValidatorEqualsAScalarSampleBySampleCheck) {
  const std::string world = GetParam();
  const auto space = make_benchmark_space(world, 6).space;
  const CSpaceOmpl s = make_cspace_ompl(space);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // The chain: uniform states. The hypercube: states near the corridor of edge k (up to 0.12
  // from it, the corridor being 0.1 wide), so that motions, between the same edge's states or
  // the next edge's, are valid or not in about equal numbers (uniform states of the 6D cube
  // are almost never in the corridor).
  const auto random_state = [&](int k) {
    State q(6);
    for (int a = 0; a < 6; ++a) {
      if (world == "chain")
        q[a] = -std::numbers::pi + 2 * std::numbers::pi * u(rng);
      else
        q[a] = a < k ? 0.12 * u(rng) : a > k ? 1.0 - 0.12 * u(rng) : u(rng);
    }
    return q;
  };
  ob::ScopedState<> sa(s.state_space), sb(s.state_space), last(s.state_space);
  int valid = 0, invalid = 0;
  for (int i = 0; i < 400; ++i) {
    const int k = static_cast<int>(u(rng) * 6);
    const State a = random_state(k);
    State b = random_state(std::min(5, k + static_cast<int>(u(rng) * 2)));
    if (i % 2 == 1)  // short: a tenth of the way to the other state
      for (int k = 0; k < 6; ++k) b[k] = a[k] + 0.1 * axis_difference(space->axes()[k], a[k], b[k]);
    set(sa, a);
    set(sb, b);
    s.state_space->enforceBounds(sb.get());
    const State b_in = values(sb.get(), 6);
    std::size_t m = 0;
    const long bad = scalar_first_invalid(*space, a, b_in, m);
    const std::uint64_t before = space->checks().value();
    std::pair<ob::State*, double> lv(last.get(), -1.0);
    const bool ok = s.si->getMotionValidator()->checkMotion(sa.get(), sb.get(), lv);
    EXPECT_EQ(space->checks().value() - before, m) << "motion " << i << ": one batch of m";
    EXPECT_EQ(s.si->checkMotion(sa.get(), sb.get()), ok);
    ASSERT_EQ(ok, bad < 0) << "motion " << i;
    if (ok) {
      ++valid;
      continue;
    }
    ++invalid;
    const double t = static_cast<double>(bad) / static_cast<double>(m);
    EXPECT_DOUBLE_EQ(lv.second, t);
    ob::ScopedState<> expect(s.state_space);
    s.state_space->interpolate(sa.get(), sb.get(), t, expect.get());
    EXPECT_EQ(values(last.get(), 6), values(expect.get(), 6));
    if (bad > 0) {  // the last valid state is a valid sample
      EXPECT_TRUE(space->is_valid(values(last.get(), 6).data()));
    }
  }
  EXPECT_GT(valid, 20) << world;
  EXPECT_GT(invalid, 20) << world;
}

INSTANTIATE_TEST_SUITE_P(ChainAndHypercube, MotionAgreement,
                         ::testing::Values("chain", "hypercube"));

// RRT-Connect on the benchmark's own query; the path's ends are the query's and every motion
// re-checks valid with the scalar test.
class RrtConnect : public ::testing::TestWithParam<std::string> {};

TEST_P(RrtConnect, SolvesDimensionFourWithAValidPath) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string world = GetParam();
  const BenchmarkSpace b = make_benchmark_space(world, 4);
  const CSpaceOmpl s = make_cspace_ompl(b.space);
  og::SimpleSetup setup(s.si);
  ob::ScopedState<> start(s.state_space), goal(s.state_space);
  set(start, b.start);
  set(goal, b.goal);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  auto planner = std::make_shared<og::RRTConnect>(s.si);
  if (world == "hypercube") planner->setRange(0.05);  // HypercubeBenchmark's
  setup.setPlanner(planner);
  ASSERT_EQ(setup.solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  const og::PathGeometric& path = setup.getSolutionPath();
  std::vector<State> points;
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    points.push_back(values(path.getState(i), 4));
  EXPECT_EQ(points.front(), b.start);
  EXPECT_LT(s.si->distance(path.getState(path.getStateCount() - 1), goal.get()), 1e-6);
  EXPECT_EQ(first_invalid_motion(*b.space, points), -1);
}

INSTANTIATE_TEST_SUITE_P(ChainAndHypercube, RrtConnect, ::testing::Values("chain", "hypercube"));

// KPIECE1 on a 2D space: through the adapter's own axes projection (OMPL 1.5's identity
// projection of a 2D real vector space aborted it on an Eigen assertion).
TEST(CSpaceOmpl, Kpiece1SolvesTheTwoDimensionalHypercube) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const BenchmarkSpace b = make_benchmark_space("hypercube", 2);
  const CSpaceOmpl s = make_cspace_ompl(b.space);
  og::SimpleSetup setup(s.si);
  ob::ScopedState<> start(s.state_space), goal(s.state_space);
  set(start, b.start);
  set(goal, b.goal);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  setup.setPlanner(std::make_shared<og::KPIECE1>(s.si));
  ASSERT_EQ(setup.solve(30.0), ob::PlannerStatus::EXACT_SOLUTION);
  std::vector<State> points;
  for (std::size_t i = 0; i < setup.getSolutionPath().getStateCount(); ++i)
    points.push_back(values(setup.getSolutionPath().getState(i), 2));
  EXPECT_EQ(first_invalid_motion(*b.space, points), -1);
}

// The grid planner inside OMPL is solve_grid on the same problem: the same lattice path, so
// the OMPL path's length is the report's cost.
class GridInOmpl : public ::testing::TestWithParam<std::string> {};

TEST_P(GridInOmpl, ReturnsSolveGridsCost) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string world = GetParam();
  const BenchmarkSpace b = make_benchmark_space(world, 4);
  const CSpaceOmpl s = make_cspace_ompl(b.space);

  GridProblem problem;
  problem.dims = 4;
  problem.extent = b.cells;
  problem.cspace = CSpaceQuery{b.space, CSpaceMoves::seed_pairs, b.start, b.goal};
  GridSearchOptions options;
  options.keep_path = true;
  const GridReport direct = solve_grid(problem, options);
  ASSERT_EQ(direct.result.status, search::Status::solved);

  og::SimpleSetup setup(s.si);
  ob::ScopedState<> start(s.state_space), goal(s.state_space);
  set(start, b.start);
  set(goal, b.goal);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  auto planner = std::make_shared<plan::CSpaceGridPlanner>(s, b.cells);
  setup.setPlanner(planner);
  const std::uint64_t before = b.space->checks().value();
  ASSERT_EQ(setup.solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  // Its lattice's checks are the space's (the report's count, plus the ends' validation).
  EXPECT_GE(b.space->checks().value() - before,
            planner->lastReport().result.counters.collision_checks);
  const og::PathGeometric& path = setup.getSolutionPath();
  EXPECT_NEAR(path.length(), direct.result.cost, 1e-9 * (1.0 + direct.result.cost));
  EXPECT_NEAR(planner->lastReport().result.cost, direct.result.cost, 1e-12);
  EXPECT_EQ(path.getStateCount(), direct.cspace->path.size());
  std::vector<State> points;
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    points.push_back(values(path.getState(i), 4));
  EXPECT_EQ(points.front(), b.start);
  EXPECT_EQ(points.back(), b.goal);
  EXPECT_EQ(first_invalid_motion(*b.space, points), -1);

  // Smoothed through OMPL's simplifier: never longer, still valid.
  setup.clear();
  planner->setSmoothing(true);
  planner->setSmoothingBudget(0.0);
  ASSERT_EQ(setup.solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_LE(setup.getSolutionPath().length(), direct.result.cost + 1e-9);
  points.clear();
  for (std::size_t i = 0; i < setup.getSolutionPath().getStateCount(); ++i)
    points.push_back(values(setup.getSolutionPath().getState(i), 4));
  EXPECT_EQ(first_invalid_motion(*b.space, points), -1);

  // Its parameters are OMPL's to set (and Benchmark's to log).
  EXPECT_TRUE(planner->params().setParam("cells", "12"));
  EXPECT_EQ(planner->getCells(), 12);
  EXPECT_TRUE(planner->params().setParam("moves", "axes"));
  EXPECT_EQ(planner->getMoves(), "axes");
}

INSTANTIATE_TEST_SUITE_P(ChainAndHypercube, GridInOmpl, ::testing::Values("chain", "hypercube"));

// The smoothed path of the 12-link chain on a 12-cell lattice: OMPL's shortcuts keep pieces of
// lattice motions whose own samples can fail (every few runs here); the planner must never
// return such a path, nor one longer than the lattice's.
TEST(GridInOmpl, SmoothedChainPathsReCheckValidAndNoLonger) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const BenchmarkSpace b = make_benchmark_space("chain", 12);
  const CSpaceOmpl s = make_cspace_ompl(b.space);
  og::SimpleSetup setup(s.si);
  ob::ScopedState<> start(s.state_space), goal(s.state_space);
  set(start, b.start);
  set(goal, b.goal);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  auto planner = std::make_shared<plan::CSpaceGridPlanner>(s, 12);
  planner->setSmoothing(true);
  setup.setPlanner(planner);
  for (int run = 0; run < 6; ++run) {
    setup.clear();
    ASSERT_EQ(setup.solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
    const og::PathGeometric& path = setup.getSolutionPath();
    EXPECT_LE(path.length(), planner->lastReport().result.cost + 1e-9) << "run " << run;
    std::vector<State> points;
    for (std::size_t i = 0; i < path.getStateCount(); ++i)
      points.push_back(values(path.getState(i), 12));
    EXPECT_EQ(first_invalid_motion(*b.space, points), -1) << "run " << run;
  }
}

TEST(CSpaceOmplBenchmark, BadOptionsAreInputErrors) {
  plan::OmplBenchOptions o;
  o.world = "chain";
  o.dims = 16;
  EXPECT_NO_THROW(plan::validate(o));
  o.dims = 17;
  EXPECT_THROW(plan::validate(o), InputError);
  o.dims = 4;
  o.world = "torus";
  EXPECT_THROW(plan::validate(o), InputError);
  o.world = "gog";
  o.dims = 11;
  EXPECT_THROW(plan::validate(o), InputError);
  o.dims = 4;
  o.cells = 8;  // c-space only
  EXPECT_THROW(plan::validate(o), InputError);
  o.cells = 0;
  o.planners = {"kpiece"};  // c-space only
  EXPECT_THROW(plan::validate(o), InputError);
  o.world = "hypercube";
  EXPECT_NO_THROW(plan::validate(o));
  o.cells = 1;
  EXPECT_THROW(plan::validate(o), InputError);
  // OMPL's own 2-link query starts in collision: refused once, before any run.
  o.cells = 0;
  o.world = "chain";
  o.dims = 2;
  o.planners = {"rrtconnect"};
  EXPECT_NO_THROW(plan::validate(o));
  EXPECT_THROW(plan::run_ompl_benchmark(o), InputError);
}

TEST(CSpaceOmplBenchmark, ChainRunsAreRecordedValidatedAndNamed) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  plan::OmplBenchOptions o;
  o.world = "chain";
  o.dims = 4;
  o.planners = {"gridastar_lattice", "rrtconnect"};
  o.runs = 2;
  o.time_s = 10.0;
  const plan::OmplBenchResult r = plan::run_ompl_benchmark(o);
  ASSERT_EQ(r.rows.size(), 4u);
  const BenchmarkSpace b = make_benchmark_space("chain", 4);
  EXPECT_EQ(r.start, b.start);
  EXPECT_EQ(r.goal, b.goal);
  EXPECT_EQ(r.cells, b.cells);
  for (const auto& row : r.rows) {
    EXPECT_TRUE(row.solved) << row.planner;
    EXPECT_TRUE(row.path_valid) << row.planner;
    EXPECT_GT(row.collision_checks, 0u) << row.planner;
    EXPECT_GE(row.quality_final, 1.0 - 1e-12) << row.planner;
  }
  EXPECT_NE(r.ompl_log.find("chain-4"), std::string::npos);
  EXPECT_NE(r.ompl_log.find("num_links INTEGER"), std::string::npos);
  EXPECT_NE(r.ompl_log.find("geometric_GridAStarLattice"), std::string::npos);
}

}  // namespace
}  // namespace hpcplan::sampling
