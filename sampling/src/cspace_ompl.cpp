#include "hpcplan/sampling/cspace_ompl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>

#include <ompl/base/ProjectionEvaluator.h>

namespace ob = ompl::base;

namespace hpcplan::sampling {

namespace {

const double* values_of(const ob::State* s) {
  return s->as<ob::RealVectorStateSpace::StateType>()->values;
}
double* values_of(ob::State* s) {
  return s->as<ob::RealVectorStateSpace::StateType>()->values;
}

// RealVectorStateSpace's own tolerance for bounds and equality.
constexpr double kEps = std::numeric_limits<double>::epsilon();

bool outside_bounded_axes(const ConfigSpace& space, const double* x) {
  const auto& axes = space.axes();
  for (std::size_t a = 0; a < axes.size(); ++a)
    if (!axes[a].periodic && (x[a] - kEps > axes[a].upper || x[a] + kEps < axes[a].lower))
      return true;
  return false;
}

// The state's coordinates as its projection, with cells a twentieth of each axis (the
// grid KPIECE1 and STRIDE's projected density count motions in).
class AxesProjection : public ob::ProjectionEvaluator {
 public:
  AxesProjection(const ob::StateSpace* space, const std::vector<AxisBounds>& axes)
      : ob::ProjectionEvaluator(space), axes_(axes) {
    bounds_ = ob::RealVectorBounds(static_cast<unsigned>(axes_.size()));
    for (std::size_t k = 0; k < axes_.size(); ++k) {
      bounds_.setLow(k, axes_[k].lower);
      bounds_.setHigh(k, axes_[k].upper);
    }
  }
  unsigned int getDimension() const override { return static_cast<unsigned>(axes_.size()); }
  void defaultCellSizes() override {
    cellSizes_.resize(axes_.size());
    for (std::size_t k = 0; k < axes_.size(); ++k)
      cellSizes_[k] = (axes_[k].upper - axes_[k].lower) / 20.0;
  }
  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    const double* x = values_of(state);
    for (std::size_t k = 0; k < axes_.size(); ++k) projection(static_cast<Eigen::Index>(k)) = x[k];
  }

 private:
  std::vector<AxisBounds> axes_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// State space

CSpaceStateSpace::CSpaceStateSpace(std::shared_ptr<const ConfigSpace> space)
    : ob::RealVectorStateSpace(static_cast<unsigned>(space->dims())), space_(std::move(space)) {
  ob::RealVectorBounds bounds(static_cast<unsigned>(space_->dims()));
  for (int a = 0; a < space_->dims(); ++a) {
    bounds.setLow(a, space_->axes()[a].lower);
    bounds.setHigh(a, space_->axes()[a].upper);
  }
  setBounds(bounds);
  setName("cspace-" + space_->name());
}

double CSpaceStateSpace::distance(const ob::State* a, const ob::State* b) const {
  // The same sum, in the same order, as Motion::length(), so a path's length here and the
  // lattice's cost of the same motions agree to the last bit.
  const double* x = values_of(a);
  const double* y = values_of(b);
  double s = 0.0;
  for (std::size_t k = 0; k < dimension_; ++k) {
    const double d = axis_difference(space_->axes()[k], x[k], y[k]);
    s += d * d;
  }
  return std::sqrt(s);
}

void CSpaceStateSpace::interpolate(const ob::State* from, const ob::State* to, double t,
                                   ob::State* state) const {
  const double* x = values_of(from);
  const double* y = values_of(to);
  double* out = values_of(state);
  // As Motion::at: the end itself at t = 1 (not from + delta's round-off), else motion_point
  // along the short-way difference.
  if (t >= 1.0) {
    std::copy(y, y + dimension_, out);
    return;
  }
  thread_local std::vector<double> delta;
  delta.resize(dimension_);
  for (std::size_t k = 0; k < dimension_; ++k)
    delta[k] = axis_difference(space_->axes()[k], x[k], y[k]);
  motion_point(space_->axes(), x, delta.data(), t, out);
}

void CSpaceStateSpace::enforceBounds(ob::State* state) const {
  double* x = values_of(state);
  const auto& axes = space_->axes();
  for (std::size_t k = 0; k < dimension_; ++k) {
    const auto& ax = axes[k];
    if (ax.periodic) {
      // A value already in range stays as it is, bit for bit: the round trip through fmod
      // would move it by an ulp, and OMPL's sanity check rejects a bound that moves states
      // inside it.
      if (x[k] >= ax.lower && x[k] < ax.upper) continue;
      const double period = ax.upper - ax.lower;
      x[k] = ax.lower + std::fmod(std::fmod(x[k] - ax.lower, period) + period, period);
      if (x[k] >= ax.upper) x[k] = ax.lower;  // fmod's round-off can land on the period
    } else {
      x[k] = std::clamp(x[k], ax.lower, ax.upper);
    }
  }
}

bool CSpaceStateSpace::satisfiesBounds(const ob::State* state) const {
  const double* x = values_of(state);
  const auto& axes = space_->axes();
  for (std::size_t k = 0; k < dimension_; ++k) {
    const auto& ax = axes[k];
    if (ax.periodic ? !(x[k] >= ax.lower && x[k] < ax.upper)
                    : (x[k] - kEps > ax.upper || x[k] + kEps < ax.lower))
      return false;
  }
  return true;
}

bool CSpaceStateSpace::equalStates(const ob::State* a, const ob::State* b) const {
  const double* x = values_of(a);
  const double* y = values_of(b);
  for (std::size_t k = 0; k < dimension_; ++k)
    if (std::abs(axis_difference(space_->axes()[k], x[k], y[k])) > kEps * 2.0) return false;
  return true;
}

double CSpaceStateSpace::getMaximumExtent() const {
  double s = 0.0;
  for (const auto& ax : space_->axes()) {
    const double w = ax.periodic ? 0.5 * (ax.upper - ax.lower) : ax.upper - ax.lower;
    s += w * w;
  }
  return std::sqrt(s);
}

void CSpaceStateSpace::registerProjections() {
  if (dimension_ > 2) {
    ob::RealVectorStateSpace::registerProjections();
    return;
  }
  registerDefaultProjection(std::make_shared<AxesProjection>(this, space_->axes()));
}

// ---------------------------------------------------------------------------------------------
// Validity

CSpaceValidityChecker::CSpaceValidityChecker(const ob::SpaceInformationPtr& si,
                                             std::shared_ptr<const ConfigSpace> space)
    : ob::StateValidityChecker(si), space_(std::move(space)) {}

bool CSpaceValidityChecker::isValid(const ob::State* state) const {
  const double* x = values_of(state);
  if (outside_bounded_axes(*space_, x)) return false;
  return space_->is_valid(x);
}

CSpaceMotionValidator::CSpaceMotionValidator(const ob::SpaceInformationPtr& si,
                                             std::shared_ptr<const ConfigSpace> space)
    : ob::MotionValidator(si), space_(std::move(space)) {}

namespace {
// One thread's scratch: a motion's samples and the batch's answers.
thread_local std::vector<double> t_samples;
thread_local std::vector<std::uint8_t> t_ok;
}  // namespace

long CSpaceMotionValidator::first_invalid(const ob::State* s1, const ob::State* s2,
                                          std::size_t& m) const {
  const std::size_t d = static_cast<std::size_t>(space_->dims());
  const double* a = values_of(s1);
  const double* b = values_of(s2);
  // An end outside the bounds fails the motion at once, as OMPL's discrete validator's
  // satisfiesBounds test does; a motion between states inside the bounds stays inside them.
  if (outside_bounded_axes(*space_, a) || outside_bounded_axes(*space_, b)) {
    m = 1;
    return 0;
  }
  const Motion motion(*space_, std::span<const double>(a, d), std::span<const double>(b, d));
  m = motion.samples(t_samples);
  t_ok.resize(m);
  space_->are_valid(t_samples.data(), m, t_ok.data());
  for (std::size_t i = 0; i < m; ++i)
    if (!t_ok[i]) return static_cast<long>(i);
  return -1;
}

bool CSpaceMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  std::size_t m = 0;
  return first_invalid(s1, s2, m) < 0;
}

bool CSpaceMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                        std::pair<ob::State*, double>& lastValid) const {
  std::size_t m = 0;
  const long bad = first_invalid(s1, s2, m);
  if (bad < 0) return true;
  // Sample i lies at t = (i + 1) / m, so the one before the first invalid sample is at
  // bad / m (s1 itself when bad is 0).
  const double t = static_cast<double>(bad) / static_cast<double>(m);
  if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, t, lastValid.first);
  lastValid.second = t;
  return false;
}

// ---------------------------------------------------------------------------------------------

CSpaceOmpl make_cspace_ompl(std::shared_ptr<const ConfigSpace> space) {
  CSpaceOmpl s;
  s.space = space;
  auto state_space = std::make_shared<CSpaceStateSpace>(space);
  s.state_space = state_space;
  s.si = std::make_shared<ob::SpaceInformation>(s.state_space);
  s.si->setStateValidityChecker(std::make_shared<CSpaceValidityChecker>(s.si, space));
  s.si->setMotionValidator(std::make_shared<CSpaceMotionValidator>(s.si, space));
  // OMPL takes the resolution as a fraction of the maximum extent in (0, 1); a space coarser
  // than its own extent still gets at least one sample per motion from the validator.
  const double fraction = space->resolution() / state_space->getMaximumExtent();
  s.si->setStateValidityCheckingResolution(std::clamp(fraction, 1e-12, 1.0 - 1e-6));
  s.si->setup();
  return s;
}

std::vector<double> cspace_values(const CSpaceOmpl& s, const ob::State* state) {
  const double* x = values_of(state);
  return {x, x + s.space->dims()};
}

long first_invalid_motion(const ConfigSpace& space, const std::vector<std::vector<double>>& path) {
  const std::size_t d = static_cast<std::size_t>(space.dims());
  std::vector<double> samples;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].size() != d) return static_cast<long>(i);
    if (i == 0) {
      if (!space.is_valid(path[0].data())) return 0;
      continue;
    }
    const std::size_t m = Motion(space, path[i - 1], path[i]).samples(samples);
    for (std::size_t k = 0; k < m; ++k)
      if (!space.is_valid(samples.data() + k * d)) return static_cast<long>(i);
  }
  return -1;
}

}  // namespace hpcplan::sampling
