#pragma once
// The reactive layer between replans (beyond seed 000, its future-work item 2): each frame it
// takes the velocity the plan follower asks for and keeps it if the robot, moving at it, stays
// clear of every obstacle it can see move over a short horizon; otherwise it picks, among
// sampled velocities, the one closest to the asked-for velocity that stays clear, or, when
// none does, the one that keeps the largest clearance. Obstacles are extrapolated at their
// current velocity (particles read from the physics frame, boxes at their own velocity): the
// seed's gas has gravity 0.02 m/s^2 and is kicked only every 5 s, so over a 0.2 s horizon
// straight-line motion is what the particles do, wall bounces and collisions aside.
//
// For each candidate velocity v and obstacle moving at u, the closest approach over [0, T] is
// exact for straight-line motion: with d = robot - obstacle and w = v - u, the gap is smallest
// at t* = clamp(-d.w / w.w, 0, T). Candidates are the asked-for velocity, zero, and 64
// directions spread evenly over the sphere (a Fibonacci lattice, plus the asked-for direction)
// at full and half speed. Only particles within reach + margin + (max speed + their speed) x
// max(T, dt) of the robot are looked at; the robot's first step (up to max speed x dt, 0.04 m at
// the seed's speed and frame) is not in that bound, so a particle up to that much farther that a
// candidate would meet within the horizon is missed (the sweeps of issue 32 ran with this bound).
//
// The seed's controller is this layer switched off (Controller::seed): the asked-for velocity
// is always used.
//
// Threads: one controller per run, called on the frame loop's thread.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "hpcplan/env/point.hpp"
#include "hpcplan/sim/safety.hpp"
#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sim {

enum class Controller { seed, reactive };
Controller parse_controller(std::string_view name);  // InputError if unknown
std::string_view to_string(Controller c);

struct ReactiveParams {
  double horizon_s = 0.2;  // how far ahead obstacles are extrapolated
  double margin = 0.03;    // clearance to keep beyond contact (m)
};

class ReactiveController {
 public:
  ReactiveController(ReactiveParams params, SafetyParams safety, double max_speed);

  // The velocity to command this frame, given the plan follower's wish. `state` must have
  // current positions and velocities (Fluid::full_state()); particles whose id is in `exclude`
  // are not obstacles (the simulator's: the goal's alone).
  // The robot moves for `dt` (one frame) at the chosen velocity before the fluid moves again.
  env::Vec<3> choose(const sph::FluidState& state, const env::Vec<3>& position,
                     const env::Vec<3>& wished, std::span<const std::uint32_t> exclude, double dt);

  // How often the wish was overridden (frames), for the run's record.
  std::uint64_t overrides() const { return overrides_; }

 private:
  struct Mover {
    env::Vec<3> at, velocity;
  };
  // The smallest clearance over the horizon when moving at v.
  double worst_clearance(const env::Vec<3>& position, const env::Vec<3>& v,
                         const sph::FluidState& state, double dt) const;

  ReactiveParams params_;
  SafetyParams safety_;
  double max_speed_;
  std::vector<env::Vec<3>> directions_;  // unit vectors
  std::vector<Mover> near_;              // particles that can come within reach this horizon
  std::vector<env::Vec<3>> candidates_;
  std::uint64_t overrides_ = 0;
};

}  // namespace hpcplan::sim
