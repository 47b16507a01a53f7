#include "hpcplan/sampling/path_tightening.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/sampling/ptc_stop.hpp"
#include "hpcplan/sampling/world_space.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::sampling {

namespace {

constexpr int kMaxDims = 16;

// The space information as a world for env's tightener: a segment is free when its first end
// is valid and OMPL's motion validator accepts the motion (the GOG harness installs the exact
// voxel walk there). Two scratch states: one view serves one run at a time.
template <int D>
class SpaceView {
 public:
  static constexpr int kDim = D;
  explicit SpaceView(const ob::SpaceInformationPtr& si)
      : si_(si), a_(si->allocState()), b_(si->allocState()) {}
  ~SpaceView() {
    si_->freeState(a_);
    si_->freeState(b_);
  }
  SpaceView(const SpaceView&) = delete;
  SpaceView& operator=(const SpaceView&) = delete;

  bool segment_free(const env::Vec<D>& p, const env::Vec<D>& q) const {
    set_state<D>(a_, p);
    set_state<D>(b_, q);
    return si_->isValid(a_) && si_->checkMotion(a_, b_);
  }

 private:
  ob::SpaceInformationPtr si_;
  ob::State* a_;
  ob::State* b_;
};

template <int D>
TighteningStats tighten_as(const ob::SpaceInformationPtr& si, og::PathGeometric& path,
                           const ob::PlannerTerminationCondition& ptc,
                           const TighteningOptions& options) {
  const SpaceView<D> view(si);
  std::vector<env::Vec<D>> points = points_of<D>(path);
  TighteningStats stats;
  stats.length_before = env::polyline_length<D>(points);
  Stopwatch clock;
  if (options.pull_string) points = env::shortcut_path(view, points);
  env::TightenOptions o;
  o.max_segment = options.max_segment;
  o.max_rounds = options.max_rounds;
  o.tolerance = 1e-5;
  // The termination condition, and the caller's own budget if it gave one.
  o.time_limit_s =
      options.time_limit_s > 0 ? std::max(0.0, options.time_limit_s - clock.seconds()) : 1e9;
  o.stop = stop_on(ptc);
  stats.rounds = env::tighten_in_place(view, points, o);
  stats.length_after = env::polyline_length<D>(points);
  set_path<D>(si, path, points);
  return stats;
}

}  // namespace

TighteningStats tighten_path(const ob::SpaceInformationPtr& si, og::PathGeometric& path,
                             const ob::PlannerTerminationCondition& ptc,
                             const TighteningOptions& options) {
  if (dynamic_cast<const ob::RealVectorStateSpace*>(si->getStateSpace().get()) == nullptr)
    throw RunError("tighten_path needs a real vector state space");
  const int dims = static_cast<int>(si->getStateDimension());
  TighteningStats stats;
  bool done = false;
  // The tightener works on fixed-size points: pick the instance for this dimension.
  [&]<int... I>(std::integer_sequence<int, I...>) {
    ((dims == I + 1 ? (stats = tighten_as<I + 1>(si, path, ptc, options), done = true) : false) ||
     ...);
  }
  (std::make_integer_sequence<int, kMaxDims>{});
  if (!done) throw RunError("tighten_path: dimension " + std::to_string(dims) + " is not in 1..16");
  return stats;
}

}  // namespace hpcplan::sampling
