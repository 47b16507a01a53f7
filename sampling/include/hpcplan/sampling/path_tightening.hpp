#pragma once
// OMPL paths through hpcplan's one tightener (env/path_shortcut.hpp): the path is read out of
// OMPL's states, tightened with the space information's validity checker and motion validator
// as the world (drop the vertices whose neighbours see each other, subdivide, slide each vertex
// towards its chord and along each axis to that axis's optimum), and written back. The length
// never grows, the ends stay exactly where they were, and every accepted motion passed the
// motion validator, so the result is as valid as the input. Complements OMPL's randomised
// shortcutting, which stalls short of the taut path around obstacle corners. Real vector
// spaces of 1 to 16 dimensions.
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>

namespace hpcplan::sampling {

struct TighteningStats {
  int rounds = 0;
  double length_before = 0.0, length_after = 0.0;
};

struct TighteningOptions {
  double max_segment = 2.0;  // subdivide longer segments (state-space units) each round
  int max_rounds = 200;
  double time_limit_s = 0.0;  // the tightener's own budget; 0 = none (ptc alone)
  // First pull the string: from each kept vertex jump to the farthest later vertex in view
  // (env::shortcut_path). On a lattice path that is most of the gain for a few checks.
  bool pull_string = false;
};

// Stops at `ptc`, at the time limit, after `max_rounds`, or when a round gains less than 1e-5
// of the length.
TighteningStats tighten_path(const ompl::base::SpaceInformationPtr& si,
                             ompl::geometric::PathGeometric& path,
                             const ompl::base::PlannerTerminationCondition& ptc,
                             const TighteningOptions& options = {});

}  // namespace hpcplan::sampling
