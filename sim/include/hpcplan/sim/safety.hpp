#pragma once
// Does the robot touch the fluid? Measured on the physics frame itself (every fluid particle
// and obstacle box where the step left them), not on the planner's world: the planner sees a
// snapshot taken up to `replan_every` frames earlier and grown obstacles, the robot meets the
// fluid as it is now.
//
// Geometry: the robot is a ball of `robot_radius` (default the seed's particle radius, 0.05);
// every fluid particle is a ball of `particle_radius` (the seed's 0.05); boxes are as the
// physics has them. Every fluid particle is an obstacle but the goal's (reaching the goal means
// touching it): the robot has no particle of its own in the fluid, the one it was drawn from
// having left the fluid when the robot took its place (simulator.hpp). Wall particles are not
// obstacles either: they stand outside the domain, and the robot's centre is kept inside it.
//
// Clearance: the signed gap between the robot's surface and the nearest obstacle surface; a
// negative clearance is an overlap of that depth. A frame is in contact when its clearance is
// below zero; a contact *event* is a frame in contact after one that was not (entering contact
// counts once, however long it lasts).
//
// Threads: free functions and a value type; no shared state.
#include <cstdint>
#include <limits>
#include <span>

#include "hpcplan/env/point.hpp"
#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sim {

struct SafetyParams {
  double robot_radius = 0.05;
  double particle_radius = 0.05;  // seed 000's particles
};

// The robot's clearance split by obstacle kind (+infinity where there is none).
struct Clearance {
  double particles = std::numeric_limits<double>::infinity();
  double boxes = std::numeric_limits<double>::infinity();
  double value() const { return particles < boxes ? particles : boxes; }
};

// Signed distance from p to the box: positive outside (Euclidean), negative inside (minus the
// distance to the nearest face), zero on a face.
double signed_distance_to_box(const sph::Box3& box, const env::Vec<3>& p);

// The clearance of a robot centred at `robot` in this frame; particles whose id is in
// `exclude` are skipped.
Clearance clearance(const sph::FluidState& state, const env::Vec<3>& robot,
                    const SafetyParams& params, std::span<const std::uint32_t> exclude);

// A run's safety figures, fed one frame at a time.
struct SafetyRecord {
  std::uint64_t contacts = 0;        // contact events
  std::uint64_t contact_frames = 0;  // frames in contact
  double contact_time_s = 0.0;       // simulated seconds in contact
  double min_clearance = std::numeric_limits<double>::infinity();
  double max_overlap = 0.0;  // deepest overlap (>= 0): max over frames of -clearance
  std::uint64_t frames = 0;  // frames observed

  // One frame of `dt` simulated seconds whose clearance was `c`.
  void observe(double c, double dt);
  // Share of the observed frames in contact (0 when none were observed).
  double contact_rate() const {
    return frames ? static_cast<double>(contact_frames) / static_cast<double>(frames) : 0.0;
  }

 private:
  bool in_contact_ = false;
};

}  // namespace hpcplan::sim
