#include "hpcplan/sim/robot.hpp"

#include <algorithm>
#include <cmath>

namespace hpcplan::sim {

Robot::Robot(env::Vec<3> position, env::Aabb<3> box, RobotParams params)
    : position_(position), box_(box), params_(params) {}

void Robot::follow(std::vector<env::Vec<3>> path) {
  path_ = std::move(path);
  next_ = 0;
  if (path_.empty()) return;
  // The plan started where the robot was when it was asked for; it has moved since. Head for
  // the waypoint after the nearest one.
  std::size_t nearest = 0;
  double best = env::distance<3>(position_, path_[0]);
  for (std::size_t i = 1; i < path_.size(); ++i)
    if (const double d = env::distance<3>(position_, path_[i]); d < best) best = d, nearest = i;
  next_ = std::min(nearest + 1, path_.size() - 1);
}

env::Vec<3> Robot::wished_velocity(double dt) {
  while (next_ < path_.size() &&
         env::distance<3>(position_, path_[next_]) <= params_.waypoint_radius &&
         next_ + 1 < path_.size())
    ++next_;
  env::Vec<3> desired{};
  if (next_ < path_.size()) {
    const double d = env::distance<3>(position_, path_[next_]);
    if (d > 1e-12) {
      // Full speed, but never past the waypoint in one step.
      const double speed = std::min(params_.max_speed, d / dt);
      for (int k = 0; k < 3; ++k) desired[k] = (path_[next_][k] - position_[k]) / d * speed;
    }
  }
  return desired;
}

void Robot::step(double dt, const env::Vec<3>& desired) {
  // a = steer_force (desired - v), applied over dt without overshooting the desired velocity.
  const double gain = std::min(1.0, params_.steer_force * dt);
  double speed2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    velocity_[k] += gain * (desired[k] - velocity_[k]);
    speed2 += velocity_[k] * velocity_[k];
  }
  if (const double speed = std::sqrt(speed2); speed > params_.max_speed)
    for (int k = 0; k < 3; ++k) velocity_[k] *= params_.max_speed / speed;
  const env::Vec<3> before = position_;
  for (int k = 0; k < 3; ++k) {
    position_[k] += velocity_[k] * dt;
    if (position_[k] < box_.lo[k]) position_[k] = box_.lo[k], velocity_[k] = 0.0;
    if (position_[k] > box_.hi[k]) position_[k] = box_.hi[k], velocity_[k] = 0.0;
  }
  travelled_ += env::distance<3>(before, position_);
}

}  // namespace hpcplan::sim
