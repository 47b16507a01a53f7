// The simulator end to end: a robot reaches its goal in an empty box and around a static box,
// and across the collapsing water column of dambreak, a sealed goal fails at the cap without
// hanging, lockstep runs repeat exactly, a plan still
// running when a run ends is cancelled, the realtime hand-off works (also under ThreadSanitizer:
// label threads), bad options are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sim/simulator.hpp"
#include "hpcplan/sph/presets.hpp"

namespace {

using namespace hpcplan;

// A 5 x 5 x 5 box holding only the robot's particle (id 0) and the goal's (id 1), at rest and
// without gravity, plus `boxes`.
sim::SimOptions scene(const env::Vec<3>& robot, const env::Vec<3>& goal,
                      std::vector<sph::Box3> boxes, const std::string& algo) {
  sim::SimOptions o;
  o.planner.algo = algo;
  // A guard only: birrt (a map3d planner here) ends at its first path, and lockstep pacing makes
  // a plan's duration irrelevant; the default 0.05 s made a slow machine's replan fail.
  o.planner.time_s = 60.0;
  o.settle_frames = 0;
  o.max_sim_s = 20.0;
  o.make_fluid = [=](std::uint64_t seed) {
    sph::FluidOptions fo;
    fo.particles = 10;
    fo.seed = seed;
    sph::FluidState s = sph::make_fluid(fo);
    s.params.gravity = {0, 0, 0};
    s.params.agitate_every = 0;
    s.domain = {{0, 0, 0}, {5, 5, 5}};
    s.particles = {};
    s.particles.add({robot[0], robot[1], robot[2]}, {0, 0, 0}, 0.0, false);
    s.particles.add({goal[0], goal[1], goal[2]}, {0, 0, 0}, 0.0, false);
    s.fluid_count = 2;
    s.boxes.clear();
    for (const sph::Box3& b : boxes) s.boxes.push_back({b, {0, 0, 0}});
    s.grid = sph::NeighbourGrid(s.domain, s.params.support);
    return s;
  };
  o.place = [](const sph::FluidState&) { return std::pair<std::uint32_t, std::uint32_t>{0, 1}; };
  return o;
}

TEST(Simulator, ReachesTheGoalInAnEmptyBox) {
  for (const std::string algo : {"astar", "astar_euclid", "dstar_lite", "rrtstar", "birrt"}) {
    const sim::SimOptions o = scene({0.5, 0.5, 0.5}, {4.5, 4.5, 4.5}, {}, algo);
    const sim::SimResult r = sim::run_simulation(o);
    ASSERT_EQ(r.runs.size(), 1u);
    const sim::RunRecord& run = r.runs[0];
    EXPECT_TRUE(run.success()) << algo << " " << sim::to_string(run.end);
    EXPECT_EQ(run.failed_replans, 0u) << algo;
    // Straight across at 2 wu/s: sqrt(48) / 2 = 3.46 s, plus the first plan's frame of delay.
    EXPECT_GT(run.sim_time_s, 3.3) << algo;
    EXPECT_LT(run.sim_time_s, 4.0) << algo;
    EXPECT_NEAR(run.avg_path_divergence, 0.0, 0.05) << algo;
  }
}

TEST(Simulator, GoesAroundAStaticBox) {
  const sph::Box3 wall{{1.5, 1.5, 0.0}, {3.5, 3.5, 5.0}};  // a pillar floor to ceiling
  for (const std::string algo : {"astar", "dstar_lite", "rrtstar"}) {
    const sim::SimOptions o = scene({0.5, 0.5, 2.5}, {4.5, 4.5, 2.5}, {wall}, algo);
    bool inside = false;
    const sim::SimResult r = sim::run_simulation(o, {}, [&](const sim::FrameView& v) {
      // The grid planner's world grows boxes by 0.2, RRT*'s does not: allow the controller's
      // corner cutting (waypoints count as passed within 0.1) for the latter.
      const double margin = algo == "rrtstar" ? 0.1 : 0.0;
      bool in = true;
      for (int k = 0; k < 2; ++k)
        in = in && v.robot[k] > wall.lo[k] + margin && v.robot[k] < wall.hi[k] - margin;
      inside = inside || in;
    });
    const sim::RunRecord& run = r.runs[0];
    EXPECT_TRUE(run.success()) << algo << " " << sim::to_string(run.end);
    EXPECT_FALSE(inside) << algo;
    EXPECT_GT(run.distance_travelled, std::sqrt(32.0) + 0.1) << algo;  // not straight through
  }
}

sim::SimOptions sealed(const std::string& algo) {
  // The goal inside a closed shell of boxes.
  const double lo = 3.0, hi = 4.4, t = 0.1;
  return scene({0.5, 0.5, 0.5}, {3.7, 3.7, 3.7},
               {{{lo, lo, lo}, {hi, hi, lo + t}},
                {{lo, lo, hi - t}, {hi, hi, hi}},
                {{lo, lo, lo}, {hi, lo + t, hi}},
                {{lo, hi - t, lo}, {hi, hi, hi}},
                {{lo, lo, lo}, {lo + t, hi, hi}},
                {{hi - t, lo, lo}, {hi, hi, hi}}},
               algo);
}

TEST(Simulator, ASealedGoalFailsAtTheCapWithoutHanging) {
  for (const std::string algo : {"astar", "dstar_lite", "rrtstar"}) {
    sim::SimOptions o = sealed(algo);
    o.max_sim_s = 3.0;
    const sim::SimResult r = sim::run_simulation(o);
    const sim::RunRecord& run = r.runs[0];
    EXPECT_FALSE(run.success()) << algo;
    EXPECT_EQ(run.end, sim::RunEnd::sim_time_cap) << algo;
    EXPECT_EQ(run.frames, 150u) << algo;
    EXPECT_GE(run.total_replans, 14u) << algo;
    EXPECT_EQ(run.failed_replans, run.total_replans) << algo;
    EXPECT_EQ(run.disconnected + run.budget, run.failed_replans) << algo;
  }
}

TEST(Simulator, LockstepRunsRepeatExactly) {
  for (const std::string algo : {"astar", "rrtstar", "dstar_lite"}) {
    sim::SimOptions o;
    o.scenario = sph::Scenario::dynamic_boxes;
    o.particles = 1500;
    o.runs = 2;
    o.seed = 7;
    o.max_sim_s = 8.0;
    o.settle_frames = 20;
    o.planner.algo = algo;
    std::vector<std::vector<double>> traces(2);
    sim::SimResult results[2];
    for (int k = 0; k < 2; ++k)
      results[k] = sim::run_simulation(o, {}, [&](const sim::FrameView& v) {
        traces[k].insert(traces[k].end(), {v.robot[0], v.robot[1], v.robot[2], v.goal[0]});
      });
    EXPECT_EQ(traces[0], traces[1]) << algo;
    ASSERT_EQ(results[0].replans.size(), results[1].replans.size()) << algo;
    for (std::size_t i = 0; i < results[0].replans.size(); ++i) {
      const auto &a = results[0].replans[i], &b = results[1].replans[i];
      EXPECT_EQ(a.frame, b.frame);
      EXPECT_EQ(a.status, b.status);
      EXPECT_EQ(a.blocked, b.blocked);
      EXPECT_EQ(a.expanded, b.expanded);
      EXPECT_EQ(a.length, b.length);
      EXPECT_EQ(a.divergence, b.divergence);
    }
    EXPECT_GT(results[0].replans.size(), 10u);
  }
}

// dambreak: the column (1 m x 1 m x 2 m, 432 particles here) falls as the run starts, so the
// first plan climbs over it; the robot crosses from one end bay to the other while the water
// spreads, and every particle stays in the tank.
TEST(Simulator, DamBreakCrossing) {
  for (const std::string algo : {"astar", "rrtstar"}) {
    sim::SimOptions o;
    o.scenario = sph::Scenario::dambreak;
    o.particles = 250;
    o.seed = 3;
    o.max_sim_s = 6.0;
    o.planner.algo = algo;
    // column_top: the highest particle over the column's footprint after 0.6 s (later the
    // surges run up the end walls and their jets fall back over the middle).
    double first_plan_top = -1.0, column_top = 0.0, lowest_x = 9, highest_x = -9;
    env::Vec<3> start{}, goal{};
    sph::Vec3 tank{};
    bool inside = true;
    const sim::SimResult r = sim::run_simulation(o, {}, [&](const sim::FrameView& v) {
      const sph::FluidState& f = *v.fluid;
      if (v.frame == 1) start = v.robot, goal = v.goal, tank = f.domain.hi;
      if (first_plan_top < 0 && !v.plan->empty())
        for (const env::Vec<3>& q : *v.plan) first_plan_top = std::max(first_plan_top, q[2]);
      for (std::size_t i = 0; i < f.particles.size(); ++i) {
        if (f.particles.wall[i]) continue;
        const sph::Vec3 x = f.particles.position(i);
        for (int k = 0; k < 3; ++k)
          inside = inside && x[k] >= f.domain.lo[k] && x[k] <= f.domain.hi[k];
        if (v.frame == 30 && x[0] > 1.5 && x[0] < 2.5) column_top = std::max(column_top, x[2]);
        lowest_x = std::min(lowest_x, x[0]), highest_x = std::max(highest_x, x[0]);
      }
      for (int k = 0; k < 3; ++k)  // the tank is 4 x 1 x 3: each axis its own extent
        inside = inside && v.robot[k] >= f.domain.lo[k] && v.robot[k] <= f.domain.hi[k];
    });
    const sim::RunRecord& run = r.runs[0];
    EXPECT_EQ(run.particle_count, 432u) << algo;  // 250 rounds to 6 x 6 x 12
    EXPECT_TRUE(run.success()) << algo << " " << sim::to_string(run.end);
    EXPECT_TRUE(inside) << algo;
    EXPECT_EQ(tank, (sph::Vec3{4.0, 1.0, 3.0})) << algo;
    // Opposite end bays, 0.2..1.0 m from the end walls (the robot has moved one frame).
    EXPECT_LT(std::min(start[0], goal[0]), 1.1) << algo;
    EXPECT_GT(std::max(start[0], goal[0]), 2.9) << algo;
    EXPECT_GT(goal[2], 0.29) << algo;
    EXPECT_GT(first_plan_top, 2.0) << algo << ": the first plan goes over the standing column";
    EXPECT_GT(column_top, 0.3) << algo;
    EXPECT_LT(column_top, 1.0) << algo << ": the column has fallen";
    EXPECT_LT(lowest_x, 1.0) << algo << ": the water spreads both ways";
    EXPECT_GT(highest_x, 3.0) << algo;
    EXPECT_GT(run.total_replans, 3u) << algo;
  }
}

TEST(SimulatorThreads, RealtimeHandOffReachesTheGoal) {
  sim::SimOptions o = scene({0.5, 0.5, 0.5}, {2.5, 2.5, 2.5}, {}, "astar");
  o.pace = sim::Pace::realtime;
  const auto t0 = std::chrono::steady_clock::now();
  const sim::SimResult r = sim::run_simulation(o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const sim::RunRecord& run = r.runs[0];
  EXPECT_TRUE(run.success()) << sim::to_string(run.end);
  EXPECT_GT(run.total_replans, 0u);
  // Paced from both sides: a frame takes at least its 0.02 s of wall time, and the run does not
  // fall behind realtime. That side is a guard, 10 times what pacing makes the run (each frame
  // its 0.02 s or its fluid step, whichever is longer: a loaded machine's steps can be longer).
  EXPECT_GE(wall, run.sim_time_s * 0.95);
  const double frames = static_cast<double>(run.frames);
  const double paced = frames * std::max(run.sim_time_s / frames, run.sph_ms_per_frame * 1e-3);
  EXPECT_LE(wall, 10.0 * paced) << run.frames << " frames, " << run.sph_ms_per_frame
                                << " ms of fluid step each (median)";
}

TEST(SimulatorThreads, ARunningPlanIsCancelledWhenTheRunEnds) {
  sim::SimOptions o = sealed("rrtstar");
  o.planner.iterations = 4'000'000'000ull;  // would run for hours
  o.pace = sim::Pace::realtime;
  o.max_sim_s = 0.3;
  // The run ends at its 0.3 s cap whatever the machine's speed (its frames are paced, the plan
  // on the other thread is what the run end must cancel; CTest's timeout catches a hang).
  const sim::SimResult r = sim::run_simulation(o);
  const sim::RunRecord& run = r.runs[0];
  EXPECT_FALSE(run.success());
  EXPECT_EQ(run.end, sim::RunEnd::sim_time_cap);
  EXPECT_EQ(run.frames, 15u);
  EXPECT_EQ(run.cancelled, 1u);
  EXPECT_EQ(run.total_replans, 0u);  // the one plan never finished
  ASSERT_EQ(r.replans.size(), 1u);
  EXPECT_EQ(r.replans[0].status, Status::cancelled);
  EXPECT_EQ(r.replans[0].reason(), "cancelled");
}

TEST(Simulator, RefusesBadOptions) {
  auto bad = [](auto change) {
    sim::SimOptions o;
    change(o);
    EXPECT_THROW(sim::validate(o), InputError);
  };
  bad([](sim::SimOptions& o) { o.particles = 1; });
  bad([](sim::SimOptions& o) { o.runs = 0; });
  bad([](sim::SimOptions& o) { o.replan_every = 0; });
  bad([](sim::SimOptions& o) { o.max_sim_s = 0; });
  bad([](sim::SimOptions& o) { o.max_wall_s = -1; });
  bad([](sim::SimOptions& o) { o.scenario = sph::Scenario::tank; });
  bad([](sim::SimOptions& o) { o.scenario = sph::Scenario::column; });  // sim: dambreak
  bad([](sim::SimOptions& o) { o.planner.algo = "nosuch"; });
  bad([](sim::SimOptions& o) { o.planner.goal_bias = 2; });
  EXPECT_THROW(sim::parse_pace("fast"), InputError);
}

}  // namespace
