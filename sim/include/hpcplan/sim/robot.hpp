#pragma once
// Seed 000's robot: a point steered towards its current waypoint by a proportional velocity
// controller (acceleration = steer_force x (desired velocity - velocity), desired = max_speed
// towards the waypoint), clamped to max_speed and kept inside the box. A waypoint counts as
// passed within `waypoint_radius`; with no plan (or past its last waypoint) the robot brakes
// under the same controller.
#include <cstddef>
#include <vector>

#include "hpcplan/env/point.hpp"

namespace hpcplan::sim {

struct RobotParams {
  double steer_force = 50.0;
  double max_speed = 2.0;
  double waypoint_radius = 0.1;
};

class Robot {
 public:
  Robot(env::Vec<3> position, env::Aabb<3> box, RobotParams params = {});

  // A new plan: its first point is where the robot was when it was asked for; the robot heads
  // for the first waypoint after the one nearest to where it is now.
  void follow(std::vector<env::Vec<3>> path);
  // The velocity the plan asks for now (passing the waypoints already reached): max_speed
  // towards the current waypoint, never past it in one step; zero with no plan.
  env::Vec<3> wished_velocity(double dt);
  // Advances by dt seconds steering towards `desired` (a reactive layer's choice).
  void step(double dt, const env::Vec<3>& desired);
  // Advances by dt seconds following the plan (the seed's controller).
  void step(double dt) { step(dt, wished_velocity(dt)); }

  const env::Vec<3>& position() const { return position_; }
  const env::Vec<3>& velocity() const { return velocity_; }
  const std::vector<env::Vec<3>>& path() const { return path_; }
  double travelled() const { return travelled_; }

 private:
  env::Vec<3> position_, velocity_{};
  env::Aabb<3> box_;
  RobotParams params_;
  std::vector<env::Vec<3>> path_;
  std::size_t next_ = 0;
  double travelled_ = 0.0;
};

}  // namespace hpcplan::sim
