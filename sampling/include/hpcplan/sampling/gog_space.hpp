#pragma once
// The GOG field as an OMPL problem whose dimension is chosen at run time (seed 002's
// comparison, 2D to 10D): env::GogWorld<d> behind the one world adapter (world_space.hpp),
// picked for the field's dimension, with the handles the harness and the grid planner need.
// One world counts every check whichever planner asks: OMPL's planners through the validity
// checker and motion validator, the grid planner by adding its lattice checks to the same
// counter.
#include <cstdint>
#include <memory>
#include <vector>

#include <ompl/base/SpaceInformation.h>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/sampling/world_space.hpp"

namespace hpcplan::sampling {

struct GogSpace {
  std::shared_ptr<const GogField> field;
  ompl::base::StateSpacePtr space;
  ompl::base::SpaceInformationPtr si;    // owns the world
  const CheckCounter* checks = nullptr;  // the world's counter
  double resolution_cells = 0.0;
  MotionCheck motion = MotionCheck::exact;
};

// InputError for a resolution outside (0, 1] cell widths or a field of more than 16
// dimensions.
GogSpace make_gog_space(std::shared_ptr<const GogField> field, double resolution_cells,
                        MotionCheck motion = MotionCheck::exact);

// Continuous centre of a lattice cell, written into `state`.
void cell_centre(const std::vector<int>& cell, ompl::base::State* state);

// Re-validates a path with direct field look-ups (counting nothing), independently of the
// planners: every waypoint must be valid, and every segment is sampled every 0.01 cell widths
// (exact motions, which guarantee every point valid) or checked by the space's own motion
// validator (discrete motions: a sampled validator only answers for its own samples). Returns
// the index of the first bad waypoint or segment, or -1 when the path is valid.
long first_invalid_step(const GogSpace& space, const std::vector<std::vector<double>>& path);

}  // namespace hpcplan::sampling
