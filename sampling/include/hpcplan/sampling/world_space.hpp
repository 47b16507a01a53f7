#pragma once
// The one OMPL adapter: any env::World (box map, sphere world, GOG field) as OMPL's space
// information, so that OMPL's planners and hpcplan's are judged on the same collision rules:
//  - space: RealVectorStateSpace(kDim) with the world's bounds;
//  - validity: the world's point_free (each call counts one check on the world's counter);
//  - motions, one of
//      exact:    WorldMotionValidator, the world's own exact segment test (default; needs no
//                resolution, cannot clip an obstacle's corner between samples);
//      discrete: OMPL's DiscreteMotionValidator, testing points along a motion no further apart
//                than `resolution` state-space units (what OMPL does out of the box).
// The space information keeps the world alive through a shared pointer; a caller that owns the
// world for longer may pass a non-owning one (make_space_information(const W&)).
//
// Threads: the validators only read the world, so one space information may serve several
// planner threads, as OMPL's own validators do.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>

#include "hpcplan/env/point.hpp"

namespace hpcplan::sampling {

enum class MotionCheck { exact, discrete };
MotionCheck parse_motion_check(std::string_view name);  // InputError if unknown

template <int D>
env::Vec<D> point_of(const ompl::base::State* s) {
  const double* v = s->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  env::Vec<D> p;
  for (int k = 0; k < D; ++k) p[k] = v[k];
  return p;
}

template <int D>
void set_state(ompl::base::State* s, const env::Vec<D>& p) {
  double* v = s->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  for (int k = 0; k < D; ++k) v[k] = p[k];
}

// An OMPL path as points, and points written back into it (its states reused where there are
// enough): for post-processing written over points, as env's smoothing is.
template <int D>
std::vector<env::Vec<D>> points_of(const ompl::geometric::PathGeometric& path) {
  std::vector<env::Vec<D>> points;
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    points.push_back(point_of<D>(path.getState(i)));
  return points;
}
template <int D>
void set_path(const ompl::base::SpaceInformationPtr& si, ompl::geometric::PathGeometric& path,
              const std::vector<env::Vec<D>>& points) {
  auto& states = path.getStates();
  while (states.size() > points.size()) {
    si->freeState(states.back());
    states.pop_back();
  }
  while (states.size() < points.size()) states.push_back(si->allocState());
  for (std::size_t i = 0; i < points.size(); ++i) set_state<D>(states[i], points[i]);
}

template <env::World W>
class WorldValidityChecker : public ompl::base::StateValidityChecker {
 public:
  WorldValidityChecker(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const W> world)
      : ompl::base::StateValidityChecker(si), world_(std::move(world)) {}
  bool isValid(const ompl::base::State* s) const override {
    return world_->point_free(point_of<W::kDim>(s));
  }

 private:
  std::shared_ptr<const W> world_;
};

template <env::World W>
class WorldMotionValidator : public ompl::base::MotionValidator {
 public:
  WorldMotionValidator(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const W> world)
      : ompl::base::MotionValidator(si), world_(std::move(world)) {}

  bool checkMotion(const ompl::base::State* a, const ompl::base::State* b) const override {
    const bool ok = world_->segment_free(point_of<W::kDim>(a), point_of<W::kDim>(b));
    (ok ? valid_ : invalid_)++;
    return ok;
  }

  // The last valid state: a world that knows where a segment first touches an obstacle
  // (first_contact) gives it exactly, stepped back by 1e-6 so the state is strictly valid;
  // any other world is bisected to within 1/64 of the motion, each prefix checked exactly.
  bool checkMotion(const ompl::base::State* a, const ompl::base::State* b,
                   std::pair<ompl::base::State*, double>& last_valid) const override {
    const auto pa = point_of<W::kDim>(a), pb = point_of<W::kDim>(b);
    double at = 0.0;
    if constexpr (requires { world_->first_contact(pa, pb); }) {
      const std::optional<double> contact = world_->first_contact(pa, pb);
      if (!contact) {
        valid_++;
        return true;
      }
      const double len = env::distance<W::kDim>(pa, pb);
      at = std::max(0.0, *contact - (len > 0.0 ? 1e-6 / len : 0.0));
      invalid_++;
    } else {
      if (checkMotion(a, b)) return true;  // counts the motion either way
      double lo = 0.0, hi = 1.0;
      for (int i = 0; i < 6; ++i) {
        const double mid = 0.5 * (lo + hi);
        (world_->segment_free(pa, env::lerp<W::kDim>(pa, pb, mid)) ? lo : hi) = mid;
      }
      at = lo;
    }
    last_valid.second = at;
    if (last_valid.first != nullptr) si_->getStateSpace()->interpolate(a, b, at, last_valid.first);
    return false;
  }

 private:
  std::shared_ptr<const W> world_;
};

struct SpaceOptions {
  MotionCheck motion = MotionCheck::exact;
  // Discrete motions: spacing of the tested points, in state-space units (0 = OMPL's default,
  // 1% of the space's diagonal). Exact motions: how finely planners that interpolate step.
  double resolution = 0.0;
};

// Builds and sets up the space information of `world`. InputError for a negative resolution.
template <env::World W>
ompl::base::SpaceInformationPtr make_space_information(std::shared_ptr<const W> world,
                                                       const SpaceOptions& options = {});

// Non-owning: the world must outlive the space information.
template <env::World W>
ompl::base::SpaceInformationPtr make_space_information(const W& world,
                                                       const SpaceOptions& options = {}) {
  return make_space_information(std::shared_ptr<const W>(std::shared_ptr<const W>(), &world),
                                options);
}

void check_resolution(double resolution);  // InputError unless finite and >= 0

template <env::World W>
ompl::base::SpaceInformationPtr make_space_information(std::shared_ptr<const W> world,
                                                       const SpaceOptions& options) {
  namespace ob = ompl::base;
  constexpr int D = W::kDim;
  check_resolution(options.resolution);
  auto space = std::make_shared<ob::RealVectorStateSpace>(D);
  ob::RealVectorBounds bounds(D);
  const env::Aabb<D> box = world->bounds();
  for (int k = 0; k < D; ++k) {
    bounds.setLow(k, box.lo[k]);
    bounds.setHigh(k, box.hi[k]);
  }
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<WorldValidityChecker<W>>(si, world));
  // OMPL's resolution is a fraction of the space's longest extent (its diagonal).
  if (options.resolution > 0.0)
    si->setStateValidityCheckingResolution(options.resolution / space->getMaximumExtent());
  if (options.motion == MotionCheck::exact)
    si->setMotionValidator(std::make_shared<WorldMotionValidator<W>>(si, world));
  si->setup();
  return si;
}

}  // namespace hpcplan::sampling
