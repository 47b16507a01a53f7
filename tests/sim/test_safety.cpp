// Does the robot touch the fluid? The safety figures against geometry worked out by hand (a
// scripted robot driven through one particle and one box), against an independent brute-force
// distance over every particle and box on every frame of a simulated run, and the reactive
// layer against the seed's controller on the same seeded scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sim/reactive_controller.hpp"
#include "hpcplan/sim/safety.hpp"
#include "hpcplan/sim/simulator.hpp"
#include "hpcplan/sph/presets.hpp"

namespace {

using namespace hpcplan;
using Vec3 = env::Vec<3>;

TEST(Safety, SignedDistanceToABox) {
  const sph::Box3 b{{0, 0, 0}, {2, 1, 1}};
  EXPECT_DOUBLE_EQ(sim::signed_distance_to_box(b, {3, 0.5, 0.5}), 1.0);            // off a face
  EXPECT_DOUBLE_EQ(sim::signed_distance_to_box(b, {3, 2, 0.5}), std::sqrt(2.0));   // an edge
  EXPECT_DOUBLE_EQ(sim::signed_distance_to_box(b, {-1, -1, -1}), std::sqrt(3.0));  // a corner
  EXPECT_DOUBLE_EQ(sim::signed_distance_to_box(b, {2, 0.5, 0.5}), 0.0);            // on a face
  EXPECT_DOUBLE_EQ(sim::signed_distance_to_box(b, {1, 0.5, 0.5}), -0.5);  // centre: y, z faces
  EXPECT_NEAR(sim::signed_distance_to_box(b, {1.9, 0.5, 0.5}), -0.1, 1e-15);
}

// One fluid particle at x = 1 and one box around x = 2.1 on the robot's line (y = z = 0.5); a
// wall particle and an excluded particle (as the goal's is) also on the line must not count.
sph::FluidState line_scene() {
  sph::FluidState s;
  s.domain = {{0, 0, 0}, {3, 1, 1}};
  s.particles.add({1.0, 0.5, 0.5}, {0, 0, 0}, 0.0, false);  // id 0: an obstacle
  s.particles.add({0.5, 0.5, 0.5}, {0, 0, 0}, 0.0, false);  // id 1: excluded
  s.particles.add({2.75, 0.5, 0.5}, {0, 0, 0}, 0.0, true);  // id 2: a wall particle
  s.fluid_count = 2;
  s.boxes.push_back({{{2.0, 0.3, 0.3}, {2.2, 0.7, 0.7}}, {0, 0, 0}});
  return s;
}

TEST(Safety, AScriptedRobotThroughAParticleAndABoxCountsTwoContacts) {
  const sph::FluidState s = line_scene();
  const sim::SafetyParams radii;  // robot 0.05, particles 0.05
  const std::uint32_t exclude[] = {1};
  sim::SafetyRecord rec;
  // x = 0.005, 0.015, ..., 2.995: half-steps, so no sample sits on a contact boundary.
  for (int i = 0; i < 300; ++i) {
    const Vec3 p{0.005 + 0.01 * i, 0.5, 0.5};
    rec.observe(sim::clearance(s, p, radii, exclude).value(), 0.02);
  }
  // The particle: centre distance < 0.1 for x in (0.9, 1.1): 20 samples. The box grown by the
  // robot's radius: x in (1.95, 2.25): 30 samples.
  EXPECT_EQ(rec.frames, 300u);
  EXPECT_EQ(rec.contacts, 2u);
  EXPECT_EQ(rec.contact_frames, 50u);
  EXPECT_NEAR(rec.contact_time_s, 1.0, 1e-12);
  // Deepest: 0.095 inside the box's x faces (y and z faces are 0.2 away) plus the radius.
  EXPECT_NEAR(rec.max_overlap, 0.145, 1e-12);
  EXPECT_NEAR(rec.min_clearance, -0.145, 1e-12);
  EXPECT_NEAR(rec.contact_rate(), 50.0 / 300.0, 1e-15);

  // Split by kind, at chosen points.
  const sim::Clearance at_particle = sim::clearance(s, {1.0, 0.5, 0.6}, radii, exclude);
  EXPECT_NEAR(at_particle.particles, -0.0, 1e-12);  // centre 0.1 away: touching, not inside
  EXPECT_NEAR(at_particle.boxes, 1.0 - 0.05, 1e-12);
  // Without the exclusion the excluded particle is the nearest.
  EXPECT_NEAR(sim::clearance(s, {0.5, 0.5, 0.5}, radii, {}).particles, -0.1, 1e-12);
  // A bigger robot touches sooner.
  sim::SafetyParams big = radii;
  big.robot_radius = 0.2;
  EXPECT_NEAR(sim::clearance(s, {0.5, 0.5, 0.5}, big, exclude).particles, 0.5 - 0.25, 1e-12);
}

TEST(Safety, ContactEventsCountEntriesNotFrames) {
  sim::SafetyRecord rec;
  for (double c : {0.1, -0.01, -0.02, 0.0, -0.03, 0.2, 0.3, -0.01}) rec.observe(c, 0.5);
  EXPECT_EQ(rec.contacts, 3u);  // 0.0 is touching, not overlapping: it ends the first contact
  EXPECT_EQ(rec.contact_frames, 4u);
  EXPECT_DOUBLE_EQ(rec.contact_time_s, 2.0);
  EXPECT_DOUBLE_EQ(rec.max_overlap, 0.03);
  EXPECT_DOUBLE_EQ(rec.min_clearance, -0.03);
}

// Independent of safety.cpp: the nearest point of the box by clamping, and depth inside as the
// nearest face.
double brute_box(const sph::Box3& b, const Vec3& p) {
  double out2 = 0.0, depth = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (int k = 0; k < 3; ++k) {
    const double c = std::clamp(p[k], b.lo[k], b.hi[k]);
    out2 += (p[k] - c) * (p[k] - c);
    inside = inside && p[k] >= b.lo[k] && p[k] <= b.hi[k];
    depth = std::min({depth, p[k] - b.lo[k], b.hi[k] - p[k]});
  }
  return inside ? -depth : std::sqrt(out2);
}

// Every particle but the goal's counts (the robot's own left the fluid: simulator.hpp).
double brute_clearance(const sph::FluidState& f, const Vec3& robot, std::uint32_t goal_id) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < f.particles.size(); ++i) {
    if (f.particles.wall[i] || f.particles.id[i] == goal_id) continue;
    const sph::Vec3 x = f.particles.position(i);
    best = std::min(best, std::hypot(x[0] - robot[0], x[1] - robot[1], x[2] - robot[2]) - 0.1);
  }
  for (const sph::MovingBox& m : f.boxes) best = std::min(best, brute_box(m.box, robot) - 0.05);
  return best;
}

TEST(Simulator, ClearanceAndContactsMatchABruteForceOnEveryFrame) {
  for (const auto scenario : {sph::Scenario::static_boxes, sph::Scenario::dynamic_boxes}) {
    sim::SimOptions o;
    o.scenario = scenario;
    o.particles = 1500;
    o.seed = 3;
    o.settle_frames = 50;
    o.max_sim_s = 6.0;
    std::uint32_t robot_id = 0, goal_id = 0;
    o.place = [&](const sph::FluidState& s) {
      const sim::Placement at = sim::place_robot_and_goal(scenario, s, 99);
      robot_id = at.robot_id, goal_id = at.goal_id;
      return std::pair{robot_id, goal_id};
    };
    std::uint64_t frames = 0, contact_frames = 0, contacts = 0;
    double worst = std::numeric_limits<double>::infinity();
    bool was_in = false;
    const sim::SimResult r = sim::run_simulation(o, {}, [&](const sim::FrameView& v) {
      ASSERT_EQ(std::count(v.fluid->particles.id.begin(), v.fluid->particles.id.end(), robot_id), 0)
          << "the robot's particle is still in the fluid at frame " << v.frame;
      const double c = brute_clearance(*v.fluid, v.robot, goal_id);
      ASSERT_NEAR(v.clearance, c, 1e-12) << "frame " << v.frame;
      ++frames;
      worst = std::min(worst, c);
      if (c < 0) contact_frames++, contacts += !was_in;
      was_in = c < 0;
    });
    const sim::RunRecord& run = r.runs[0];
    EXPECT_EQ(run.frames, frames);
    EXPECT_EQ(run.contact_frames, contact_frames);
    EXPECT_EQ(run.contacts, contacts);
    EXPECT_NEAR(run.contact_time_s, 0.02 * static_cast<double>(contact_frames), 1e-9);
    EXPECT_DOUBLE_EQ(run.min_clearance, worst);
    EXPECT_DOUBLE_EQ(run.max_overlap, std::max(0.0, -worst));
    // The seed's controller does run into the fluid on these scenes: the counts are exercised.
    EXPECT_GT(contact_frames, 0u) << sph::to_string(scenario);
    EXPECT_EQ(run.controller, "seed");
  }
}

TEST(Simulator, TheReactiveLayerNeverAddsContactsAndReachesTheGoal) {
  for (const std::string algo : {"astar", "rrtstar"})
    for (const auto scenario : {sph::Scenario::particles, sph::Scenario::dynamic_boxes}) {
      sim::SimOptions o;
      o.scenario = scenario;
      o.particles = 1500;
      o.seed = 3;
      o.runs = 2;
      o.settle_frames = 50;
      o.max_sim_s = 30.0;
      o.planner.algo = algo;
      const sim::SimResult plain = sim::run_simulation(o);
      o.controller = sim::Controller::reactive;
      const sim::SimResult reactive = sim::run_simulation(o);
      std::uint64_t plain_frames = 0, reactive_frames = 0;
      for (int k = 0; k < 2; ++k) {
        const sim::RunRecord &p = plain.runs[k], &q = reactive.runs[k];
        EXPECT_TRUE(q.success()) << algo << " run " << k + 1 << ": " << sim::to_string(q.end);
        EXPECT_LE(q.contact_frames, p.contact_frames) << algo << " run " << k + 1;
        EXPECT_GT(q.reactive_overrides, 0u) << algo;
        EXPECT_EQ(q.controller, "reactive");
        plain_frames += p.contact_frames;
        reactive_frames += q.contact_frames;
      }
      // Without the layer these scenes have contacts; with it, none.
      EXPECT_GT(plain_frames, 0u) << algo << " " << sph::to_string(scenario);
      EXPECT_EQ(reactive_frames, 0u) << algo << " " << sph::to_string(scenario);
    }
}

TEST(Simulator, RefusesBadSafetyOptions) {
  auto bad = [](auto change) {
    sim::SimOptions o;
    change(o);
    EXPECT_THROW(sim::validate(o), InputError);
  };
  bad([](sim::SimOptions& o) { o.safety.robot_radius = -0.1; });
  bad([](sim::SimOptions& o) { o.safety.robot_radius = std::nan(""); });
  bad([](sim::SimOptions& o) { o.reactive.horizon_s = 0; });
  bad([](sim::SimOptions& o) { o.reactive.margin = -1; });
  EXPECT_THROW(sim::parse_controller("fast"), InputError);
  EXPECT_EQ(sim::parse_controller("reactive"), sim::Controller::reactive);
}

}  // namespace
