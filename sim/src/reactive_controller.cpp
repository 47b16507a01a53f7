#include "hpcplan/sim/reactive_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "hpcplan/core/error.hpp"

namespace hpcplan::sim {

Controller parse_controller(std::string_view name) {
  if (name == "seed") return Controller::seed;
  if (name == "reactive") return Controller::reactive;
  throw InputError("unknown --controller " + std::string(name) + " (seed or reactive)");
}

std::string_view to_string(Controller c) {
  return c == Controller::reactive ? "reactive" : "seed";
}

namespace {

using Vec3 = env::Vec<3>;

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The smallest |d + w t| for t in [0, horizon].
double closest_approach(const Vec3& d, const Vec3& w, double horizon) {
  const double ww = dot(w, w);
  const double t = ww > 0.0 ? std::clamp(-dot(d, w) / ww, 0.0, horizon) : 0.0;
  const Vec3 at{d[0] + w[0] * t, d[1] + w[1] * t, d[2] + w[2] * t};
  return std::sqrt(dot(at, at));
}

constexpr int kDirections = 64;
constexpr int kBoxSamples = 8;  // box clearance is sampled along the horizon

}  // namespace

ReactiveController::ReactiveController(ReactiveParams params, SafetyParams safety, double max_speed)
    : params_(params), safety_(safety), max_speed_(max_speed) {
  if (!(params_.horizon_s > 0.0) || !(params_.margin >= 0.0))
    throw InputError("the reactive horizon must be positive and its margin >= 0");
  // Fibonacci lattice: z evenly spaced, longitude advancing by the golden angle.
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / kDirections;
    const double r = std::sqrt(1.0 - z * z);
    directions_.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
  }
}

double ReactiveController::worst_clearance(const Vec3& position, const Vec3& v,
                                           const sph::FluidState& state, double dt) const {
  const double T = params_.horizon_s;
  const double reach = safety_.robot_radius + safety_.particle_radius;
  double worst = std::numeric_limits<double>::infinity();
  for (const Mover& m : near_) {
    const Vec3 d{position[0] - m.at[0], position[1] - m.at[1], position[2] - m.at[2]};
    const Vec3 w{v[0] - m.velocity[0], v[1] - m.velocity[1], v[2] - m.velocity[2]};
    // The frame loop moves the robot after the fluid's frame: its next position meets the
    // obstacles where they are now; from there both move on. (Measuring from the robot's
    // present position instead would make every candidate as bad as an overlap it is in now.)
    const Vec3 next{d[0] + v[0] * dt, d[1] + v[1] * dt, d[2] + v[2] * dt};
    worst = std::min(worst, closest_approach(next, w, T) - reach);
  }
  for (const sph::MovingBox& b : state.boxes)
    for (int s = 0; s <= kBoxSamples; ++s) {
      const double t = T * s / kBoxSamples;
      // The robot relative to the box, which moves at its own velocity.
      const Vec3 p{position[0] + v[0] * dt + (v[0] - b.velocity[0]) * t,
                   position[1] + v[1] * dt + (v[1] - b.velocity[1]) * t,
                   position[2] + v[2] * dt + (v[2] - b.velocity[2]) * t};
      worst = std::min(worst, signed_distance_to_box(b.box, p) - safety_.robot_radius);
    }
  return worst;
}

Vec3 ReactiveController::choose(const sph::FluidState& state, const Vec3& position,
                                const Vec3& wished, std::span<const std::uint32_t> exclude,
                                double dt) {
  // Particles that could come within reach (plus the margin) within the horizon at any
  // candidate velocity: centre distance minus what both can travel.
  const double T = params_.horizon_s;
  const double reach = safety_.robot_radius + safety_.particle_radius + params_.margin;
  const sph::Particles& p = state.particles;
  near_.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i]) continue;
    const double dx = p.x[i] - position[0], dy = p.y[i] - position[1], dz = p.z[i] - position[2];
    const double speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    const double limit = reach + (max_speed_ + speed) * std::max(T, dt);
    if (dx * dx + dy * dy + dz * dz > limit * limit) continue;
    if (std::find(exclude.begin(), exclude.end(), p.id[i]) != exclude.end()) continue;
    near_.push_back({{p.x[i], p.y[i], p.z[i]}, {p.vx[i], p.vy[i], p.vz[i]}});
  }
  if (near_.empty() && state.boxes.empty()) return wished;
  if (worst_clearance(position, wished, state, dt) >= params_.margin) return wished;

  ++overrides_;
  candidates_.clear();
  candidates_.push_back({0.0, 0.0, 0.0});
  const double wished_speed = std::sqrt(dot(wished, wished));
  if (wished_speed > 0.0) {
    candidates_.push_back(
        {wished[0] / wished_speed, wished[1] / wished_speed, wished[2] / wished_speed});
    for (double& x : candidates_.back()) x *= max_speed_;
  }
  for (const Vec3& u : directions_)
    for (const double s : {max_speed_, 0.5 * max_speed_})
      candidates_.push_back({u[0] * s, u[1] * s, u[2] * s});

  // Safe candidates: the one nearest the wish. None safe: the largest clearance (ties: nearer
  // the wish).
  Vec3 best = wished;
  bool best_safe = false;
  double best_gap = -std::numeric_limits<double>::infinity(), best_off = 0.0;
  for (const Vec3& v : candidates_) {
    const double gap = worst_clearance(position, v, state, dt);
    const Vec3 off{v[0] - wished[0], v[1] - wished[1], v[2] - wished[2]};
    const double dist = dot(off, off);
    const bool safe = gap >= params_.margin;
    const bool better =
        safe ? (!best_safe || dist < best_off)
             : (!best_safe && (gap > best_gap || (gap == best_gap && dist < best_off)));
    if (better) best = v, best_safe = safe, best_gap = gap, best_off = dist;
  }
  return best;
}

}  // namespace hpcplan::sim
