#pragma once
// A configuration space (env/config_space.hpp: the kinematic chain, the hypercube, a user's
// space) as an OMPL problem, so OMPL's planners and the lattice planner of the same space
// (plan/cspace_grid_planner.hpp) are compared on one metric, one set of motion checks and one
// collision-check counter.
//
//  - CSpaceStateSpace: a RealVectorStateSpace with the space's bounds whose distance is the
//    Euclidean length in the space's own coordinates, periodic axes measured the short way:
//    the lattice's edge costs and the length every planner of the comparison reports. OMPL's
//    KinematicChainBenchmark measures its chain in the workspace (where the links' ends
//    move); we deliberately use the joint-space metric instead, so that a chain path's
//    length means the same thing whichever planner found it. interpolate() is Motion's
//    (config_space.hpp: motion_point along axis_difference), so a motion OMPL interpolates
//    passes through the very states a lattice edge tests; periodic axes wrap into
//    [lower, upper).
//  - CSpaceValidityChecker: the space's one-state test.
//  - CSpaceMotionValidator: a motion's samples (Motion::samples, at the space's resolution:
//    the samples a lattice edge tests) as ONE batch through ConfigSpace::are_valid, so a
//    space whose test vectorises over states (VAMP's idea) answers a whole motion at once.
//    The whole batch is tested even when an early sample fails: every sample counts as a
//    collision check.
//
// Threads: the ConfigSpace is immutable and its tests are safe from any number of threads
// (its CheckCounter is atomic). The state space, the checker and the motion validator are
// stateless (scratch buffers are thread-local; the validator leaves OMPL's unsynchronised
// valid/invalid tallies at zero: the space's counter is the one count), so planners that
// check from several threads (PRM's roadmap thread) may share them.
#include <cstdint>
#include <memory>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "hpcplan/env/config_space.hpp"

namespace hpcplan::sampling {

class CSpaceStateSpace : public ompl::base::RealVectorStateSpace {
 public:
  explicit CSpaceStateSpace(std::shared_ptr<const ConfigSpace> space);

  const ConfigSpace& config_space() const { return *space_; }

  double distance(const ompl::base::State* a, const ompl::base::State* b) const override;
  void interpolate(const ompl::base::State* from, const ompl::base::State* to, double t,
                   ompl::base::State* state) const override;
  // Periodic axes wrap into [lower, upper); bounded ones clamp (RealVectorStateSpace's rule).
  void enforceBounds(ompl::base::State* state) const override;
  bool satisfiesBounds(const ompl::base::State* state) const override;
  // Equal within OMPL's tolerance, periodic axes compared the short way (-pi is pi).
  bool equalStates(const ompl::base::State* a, const ompl::base::State* b) const override;
  // The largest distance two states can have in this metric: half a period on a periodic
  // axis, the full width on a bounded one. Resolution fractions refer to it.
  double getMaximumExtent() const override;
  // KPIECE1 and STRIDE's default projection: OMPL's random linear one from 3 axes up; below,
  // the axes themselves through a projection of our own (OMPL 1.5's identity projection of a
  // 2D real vector space fails an Eigen assertion and aborts in KPIECE1).
  void registerProjections() override;

 private:
  std::shared_ptr<const ConfigSpace> space_;
};

class CSpaceValidityChecker : public ompl::base::StateValidityChecker {
 public:
  CSpaceValidityChecker(const ompl::base::SpaceInformationPtr& si,
                        std::shared_ptr<const ConfigSpace> space);
  // Outside the bounds on a bounded axis: invalid, uncounted (the space's test need not look
  // at bounds; OMPL's samplers stay inside them anyway). Otherwise the space's test (one
  // check).
  bool isValid(const ompl::base::State* state) const override;

 private:
  std::shared_ptr<const ConfigSpace> space_;
};

class CSpaceMotionValidator : public ompl::base::MotionValidator {
 public:
  CSpaceMotionValidator(const ompl::base::SpaceInformationPtr& si,
                        std::shared_ptr<const ConfigSpace> space);
  // Whether every sample of the motion s1 -> s2 is valid (s1 itself is not tested: it is the
  // previous state of a path, tested already; s2 is the last sample).
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  // The same; on failure lastValid gets the last valid sample before the first invalid one
  // (s1 itself, t = 0, when the first sample fails) and its fraction of the motion.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  // Index of the first invalid sample, or -1; the samples are left in the scratch buffer,
  // m of them.
  long first_invalid(const ompl::base::State* s1, const ompl::base::State* s2,
                     std::size_t& m) const;

  std::shared_ptr<const ConfigSpace> space_;
};

struct CSpaceOmpl {
  std::shared_ptr<const ConfigSpace> space;
  ompl::base::StateSpacePtr state_space;  // a CSpaceStateSpace
  ompl::base::SpaceInformationPtr si;     // set up: checker, motion validator, resolution
};

// The space as an OMPL problem. si's state-validity-checking resolution is the space's
// resolution over the metric's maximum extent, so planners that read it (and OMPL's own
// discrete validator, were one installed) sample motions as finely as the lattice does.
CSpaceOmpl make_cspace_ompl(std::shared_ptr<const ConfigSpace> space);

// The coordinates of an OMPL state of such a space.
std::vector<double> cspace_values(const CSpaceOmpl& s, const ompl::base::State* state);

// Re-checks a path independently of OMPL's validator: its first state with the space's
// one-state test, then every motion's samples (Motion::samples) one at a time. Returns the
// index of the first bad state or motion, or -1 when the path is valid. Counts its checks on
// the space's counter (read the counter before calling it to exclude them).
long first_invalid_motion(const ConfigSpace& space, const std::vector<std::vector<double>>& path);

}  // namespace hpcplan::sampling
