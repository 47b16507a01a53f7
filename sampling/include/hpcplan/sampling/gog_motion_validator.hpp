#pragma once
// Exact motion validation on the GOG grid: a straight motion is valid iff every lattice cell
// whose closed box the segment touches is free (a d-dimensional voxel walk, Amanatides-Woo,
// where crossing an edge or corner of several cells at once checks every cell meeting there).
// Touching counts, so a motion can never slip between two blocked cells that share only a
// corner: the same no-corner-cutting rule as the lattice's diagonal moves. This is stricter
// than "every point on the segment is valid", so a motion it accepts is valid at any sampling
// resolution; it needs no resolution and cannot miss a thin corner between samples.
// Each cell looked up counts as one collision check on the world's checker.
#include <ompl/base/MotionValidator.h>

#include "hpcplan/sampling/gog_world.hpp"

namespace hpcplan::sampling {

class GogMotionValidator : public ompl::base::MotionValidator {
 public:
  GogMotionValidator(const ompl::base::SpaceInformationPtr& si,
                     std::shared_ptr<const GogValidityChecker> checker);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& last_valid) const override;

  // The walk on raw coordinates: returns true when free; otherwise `blocked_at` is the
  // segment parameter in [0, 1] where the first blocked cell is touched.
  bool segment_free(const double* a, const double* b, double* blocked_at) const;

 private:
  std::shared_ptr<const GogValidityChecker> checker_;
};

}  // namespace hpcplan::sampling
