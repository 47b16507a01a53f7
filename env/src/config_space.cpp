#include "hpcplan/env/config_space.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "hpcplan/core/error.hpp"

namespace hpcplan {
namespace {

std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

ConfigSpace::ConfigSpace(std::string name, std::vector<AxisBounds> axes, double resolution)
    : name_(std::move(name)), axes_(std::move(axes)), resolution_(resolution) {
  if (axes_.empty()) throw InputError(name_ + ": a configuration space needs at least one axis");
  for (std::size_t a = 0; a < axes_.size(); ++a) {
    const auto& ax = axes_[a];
    if (!std::isfinite(ax.lower) || !std::isfinite(ax.upper) || !(ax.lower < ax.upper))
      throw InputError(name_ + ": axis " + std::to_string(a) +
                       " needs finite bounds with lower < upper");
  }
  const double extent = maximum_extent();
  if (!std::isfinite(extent) || !(extent > 0.0))
    throw InputError(name_ + ": the bounds' diagonal is not a finite positive length");
  set_resolution(resolution);
}

void ConfigSpace::set_resolution(double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution))
    throw InputError(name_ + ": the motion-check resolution must be positive");
  // A motion across the whole space is sampled at most kMaxMotionSamples times: finer steps
  // would make single motions (and one expansion's batch) run for minutes and past memory, and
  // a step count past 2^64 would be no count at all.
  if (!(maximum_extent() / resolution <= kMaxMotionSamples))
    throw InputError(name_ + ": the motion-check step " + shortest(resolution) +
                     " would need more than " +
                     std::to_string(static_cast<long long>(kMaxMotionSamples)) +
                     " samples across the space (a resolution fraction of at least 1e-7)");
  resolution_ = resolution;
}

double ConfigSpace::maximum_extent() const {
  double s = 0.0;
  for (const auto& a : axes_) s += (a.upper - a.lower) * (a.upper - a.lower);
  return std::sqrt(s);
}

bool ConfigSpace::in_bounds(std::span<const double> state) const {
  if (state.size() != axes_.size()) return false;
  for (std::size_t a = 0; a < axes_.size(); ++a) {
    const auto& ax = axes_[a];
    const double v = state[a];
    if (!(v >= ax.lower) || (ax.periodic ? !(v < ax.upper) : !(v <= ax.upper))) return false;
  }
  return true;
}

void ConfigSpace::valid_batch(const double* states, std::size_t k, std::uint8_t* out) const {
  const std::size_t d = axes_.size();
  for (std::size_t i = 0; i < k; ++i) out[i] = valid(states + i * d) ? 1 : 0;
}

double axis_difference(const AxisBounds& axis, double from, double to) {
  double d = to - from;
  if (axis.periodic) {
    // In [-period/2, period/2]. Values in the bounds are less than a period apart, so one
    // period added or taken off is enough; std::remainder (4x slower, and this is on every
    // lattice edge and heuristic) only for values from outside them.
    const double period = axis.upper - axis.lower;
    const double half = 0.5 * period;
    if (d > half)
      d -= period;
    else if (d < -half)
      d += period;
    if (d > half || d < -half) d = std::remainder(to - from, period);
  }
  return d;
}

Motion::Motion(const ConfigSpace& space, std::span<const double> from, std::span<const double> to)
    : space_(space),
      from_(from.begin(), from.end()),
      to_(to.begin(), to.end()),
      delta_(from.size()) {
  double s = 0.0;
  for (std::size_t a = 0; a < from.size(); ++a) {
    delta_[a] = axis_difference(space.axes()[a], from[a], to[a]);
    s += delta_[a] * delta_[a];
  }
  length_ = std::sqrt(s);
}

std::size_t motion_steps(double length, double resolution) {
  const double steps = std::ceil(length / resolution - 1e-12);
  // Motions inside a space are at most kMaxMotionSamples steps (set_resolution); a longer one
  // (a length from outside the bounds) is an error, not a conversion past size_t's range.
  if (!(steps <= 4.0 * kMaxMotionSamples))
    throw RunError("a motion of length " + std::to_string(length) + " needs " +
                   std::to_string(steps) + " samples at step " + std::to_string(resolution));
  return std::max<std::size_t>(1, static_cast<std::size_t>(steps));
}

void motion_point(const std::vector<AxisBounds>& axes, const double* from, const double* delta,
                  double t, double* out) {
  for (std::size_t a = 0; a < axes.size(); ++a) {
    double v = from[a] + t * delta[a];
    if (axes[a].periodic) {
      const double period = axes[a].upper - axes[a].lower;
      if (v >= axes[a].upper)
        v -= period;
      else if (v < axes[a].lower)
        v += period;
    }
    out[a] = v;
  }
}

void Motion::at(double t, double* out) const {
  if (t >= 1.0) {  // the end itself, not from + delta's round-off (a lattice vertex stays one)
    std::copy(to_.begin(), to_.end(), out);
    return;
  }
  motion_point(space_.axes(), from_.data(), delta_.data(), t, out);
}

std::size_t Motion::samples(std::vector<double>& out) const {
  const std::size_t m = motion_steps(length_, space_.resolution());
  const std::size_t d = from_.size();
  out.resize(m * d);
  for (std::size_t i = 1; i <= m; ++i)
    at(static_cast<double>(i) / static_cast<double>(m), out.data() + (i - 1) * d);
  return m;
}

bool motion_valid(const ConfigSpace& space, std::span<const double> from,
                  std::span<const double> to) {
  std::vector<double> states;
  const std::size_t m = Motion(space, from, to).samples(states);
  std::vector<std::uint8_t> ok(m);
  space.are_valid(states.data(), m, ok.data());
  for (auto v : ok)
    if (!v) return false;
  return true;
}

}  // namespace hpcplan
