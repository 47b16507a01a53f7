#pragma once
// Pulls a valid geometric path taut without leaving its homotopy class: each interior waypoint
// moves toward the midpoint of its neighbours (step 1, 1/2, 1/4, 1/8 of the way, first that keeps
// both adjacent motions valid), segments are subdivided so corners can round off, and redundant
// waypoints are dropped whenever the motion that skips them is valid. The length never grows
// and every accepted motion passes the space information's motion validator, so the result is
// as valid as the input. Complements OMPL's randomised shortcutting, which stalls short of the
// taut path around obstacle corners.
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>

namespace hpcplan::sampling {

struct TighteningStats {
  int rounds = 0;
  double length_before = 0.0, length_after = 0.0;
};

// `max_segment`: subdivide segments longer than this (state-space units) once per round.
TighteningStats tighten_path(const ompl::base::SpaceInformationPtr& si,
                             ompl::geometric::PathGeometric& path,
                             const ompl::base::PlannerTerminationCondition& ptc, double max_segment,
                             int max_rounds = 200);

}  // namespace hpcplan::sampling
