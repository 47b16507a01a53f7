// The robot's particle (issue 46): the robot takes the place of the particle it was drawn from,
// and that particle leaves the fluid, so that nothing in the fluid is invisible to the
// planners, the reactive layer and the contact metric (the goal's particle, the target, aside).
// Before, the particle stayed in the fluid and moved with it while all three skipped it: the
// scene below, a robot particle drifting along the robot's way, had the robot overlap it for
// frames that counted as clear.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sim/simulator.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/presets.hpp"

namespace {

using namespace hpcplan;
using Vec3 = env::Vec<3>;

// The robot's clearance against every particle the frame holds but the goal's (walls aside:
// they stand outside the domain), by brute force; +infinity with none.
double clearance_to_all_but_goal(const sph::FluidState& f, const Vec3& robot,
                                 std::uint32_t goal_id) {
  double best = std::numeric_limits<double>::infinity();
  const sph::Particles& p = f.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i] || p.id[i] == goal_id) continue;
    best = std::min(best, std::hypot(p.x[i] - robot[0], p.y[i] - robot[1], p.z[i] - robot[2]) -
                              0.1);  // two balls of 0.05
  }
  for (const sph::MovingBox& m : f.boxes)
    best = std::min(best, sim::signed_distance_to_box(m.box, robot) - 0.05);
  return best;
}

// Equal up to round-off (safety.cpp sums the radii in another order), or both +infinity.
::testing::AssertionResult same_clearance(double reported, double brute) {
  if (reported == brute || std::abs(reported - brute) <= 1e-12)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "reported " << reported << ", brute force " << brute;
}

bool holds_id(const sph::FluidState& f, std::uint32_t id) {
  return std::find(f.particles.id.begin(), f.particles.id.end(), id) != f.particles.id.end();
}

// A 5 x 5 x 5 box without gravity or agitation holding the robot's particle (id 0) at the
// robot's start, moving at 1 m/s along the robot's way (+x), and the goal's (id 1) at rest 4 m
// on. The robot stands still for its first frame (its first plan comes a frame later) while its
// particle drifts 0.02 on, then overtakes it at 2 m/s: left in the fluid, the particle is within
// 0.1 of the robot's centre (contact by the seed's radii) in the first frames.
sim::SimOptions drifting_particle_scene(sim::Controller controller) {
  sim::SimOptions o;
  o.planner.algo = "astar";
  o.planner.time_s = 60.0;  // a guard only (lockstep pacing)
  o.settle_frames = 0;
  o.max_sim_s = 5.0;
  o.controller = controller;
  o.make_fluid = [](std::uint64_t seed) {
    sph::FluidOptions fo;
    fo.particles = 10;
    fo.seed = seed;
    sph::FluidState s = sph::make_fluid(fo);
    s.params.gravity = {0, 0, 0};
    s.params.agitate_every = 0;
    s.domain = {{0, 0, 0}, {5, 5, 5}};
    s.particles = {};
    s.particles.add({0.5, 2.5, 2.5}, {1.0, 0, 0}, 0.0, false);  // the robot's
    s.particles.add({4.5, 2.5, 2.5}, {0, 0, 0}, 0.0, false);    // the goal's
    s.fluid_count = 2;
    s.boxes.clear();
    s.grid = sph::NeighbourGrid(s.domain, s.params.support);
    return s;
  };
  o.place = [](const sph::FluidState&) { return std::pair<std::uint32_t, std::uint32_t>{0, 1}; };
  return o;
}

TEST(RobotParticle, WithoutParticleTakesOutThatParticleAlone) {
  sph::FluidOptions fo;
  fo.particles = 200;
  fo.seed = 5;
  sph::Fluid fluid(sph::make_fluid(fo), "cpu");
  for (int f = 0; f < 20; ++f) ASSERT_EQ(fluid.advance_frame().problem, "");  // reordered by now
  const sph::FluidState before = fluid.full_state();
  const sph::Particles& p = before.particles;
  const std::size_t at = p.size() / 3;
  const std::uint32_t id = p.id[at];
  const sph::FluidState after = sim::without_particle(before, id);
  const sph::Particles& q = after.particles;
  ASSERT_EQ(q.size(), p.size() - 1);
  EXPECT_EQ(after.fluid_count, before.fluid_count - 1);
  EXPECT_FALSE(holds_id(after, id));
  for (std::size_t i = 0; i < q.size(); ++i) {  // every other particle, in its order
    const std::size_t j = i < at ? i : i + 1;
    ASSERT_EQ(q.id[i], p.id[j]) << i;
    EXPECT_EQ(q.position(i), p.position(j)) << i;
    EXPECT_EQ(q.velocity(i), p.velocity(j)) << i;
    EXPECT_EQ(q.rho[i], p.rho[j]) << i;
  }
  EXPECT_EQ(after.time, before.time);
  EXPECT_EQ(after.substeps, before.substeps);
  EXPECT_THROW(sim::without_particle(before, 1u << 30), RunError);
  // The fluid goes on from it.
  sph::Fluid rest(after, "cpu", fluid.frames_done());
  for (int f = 0; f < 20; ++f) ASSERT_EQ(rest.advance_frame().problem, "");
  EXPECT_EQ(rest.state().particles.size(), q.size());
}

// The case the old rule hid: with either controller, the run's clearance and contacts are
// those of every particle the fluid holds but the goal's, and the robot's particle is not in
// the fluid. (Before: the particle overlapped the robot in the first frames and the run
// reported no contact.)
TEST(RobotParticle, NoParticleTheRobotMeetsIsHidden) {
  for (const auto controller : {sim::Controller::seed, sim::Controller::reactive}) {
    const std::string name(sim::to_string(controller));
    std::uint64_t frames = 0, contact_frames = 0;
    const sim::SimResult r =
        sim::run_simulation(drifting_particle_scene(controller), {}, [&](const sim::FrameView& v) {
          EXPECT_FALSE(holds_id(*v.fluid, 0)) << name << " frame " << v.frame;
          EXPECT_TRUE(holds_id(*v.fluid, 1)) << name << " frame " << v.frame;
          EXPECT_EQ(v.fluid->fluid_count, 1u) << name << " frame " << v.frame;
          const double c = clearance_to_all_but_goal(*v.fluid, v.robot, 1);
          EXPECT_TRUE(same_clearance(v.clearance, c)) << name << " frame " << v.frame;
          ++frames;
          contact_frames += c < 0;
        });
    ASSERT_EQ(r.runs.size(), 1u);
    const sim::RunRecord& run = r.runs[0];
    EXPECT_TRUE(run.success()) << name << " " << sim::to_string(run.end);
    EXPECT_EQ(run.frames, frames) << name;
    EXPECT_EQ(run.contact_frames, contact_frames) << name;
    EXPECT_EQ(run.particle_count, 2u) << name;  // the fluid as built
  }
}

// The seed's scenarios: the robot's particle leaves the fluid when the robot is placed, and
// the fluid holds every other particle from then on.
TEST(RobotParticle, LeavesTheSeedsFluidWhenTheRobotIsPlaced) {
  for (const auto scenario : {sph::Scenario::particles, sph::Scenario::dynamic_boxes}) {
    sim::SimOptions o;
    o.scenario = scenario;
    o.particles = 600;
    o.seed = 7;
    o.settle_frames = 20;
    o.max_sim_s = 1.0;
    std::uint32_t robot_id = sim::kNoParticle, goal_id = sim::kNoParticle;
    std::size_t built = 0;
    o.place = [&](const sph::FluidState& s) {
      built = s.fluid_count;
      const sim::Placement at = sim::place_robot_and_goal(scenario, s, 99);
      robot_id = at.robot_id, goal_id = at.goal_id;
      return std::pair{robot_id, goal_id};
    };
    std::uint64_t frames = 0;
    const sim::SimResult r = sim::run_simulation(o, {}, [&](const sim::FrameView& v) {
      ASSERT_FALSE(holds_id(*v.fluid, robot_id)) << "frame " << v.frame;
      ASSERT_TRUE(holds_id(*v.fluid, goal_id)) << "frame " << v.frame;
      ASSERT_EQ(v.fluid->fluid_count, built - 1) << "frame " << v.frame;
      ASSERT_TRUE(
          same_clearance(v.clearance, clearance_to_all_but_goal(*v.fluid, v.robot, goal_id)))
          << "frame " << v.frame;
      ++frames;
    });
    EXPECT_EQ(r.runs[0].frames, frames);
    EXPECT_EQ(r.runs[0].particle_count, built);
  }
}

}  // namespace
