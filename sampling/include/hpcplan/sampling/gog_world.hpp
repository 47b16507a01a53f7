#pragma once
// The GOG field as OMPL sees it, so that OMPL's planners and the grid planners solve the same
// problem through the same checker:
//  - space: RealVectorStateSpace(d) with bounds [0, extent] on every axis;
//  - validity: a point is valid iff the lattice cell holding it is free, the cell of x being
//    floor(x) per axis (x = extent, the upper bound, belongs to the last cell);
//  - motions, one of
//      exact:    GogMotionValidator, a voxel walk that accepts a segment iff every cell it
//                touches is free (default; no resolution involved);
//      discrete: OMPL's DiscreteMotionValidator, which tests points along a segment no further
//                apart than `resolution_cells` cell widths (what OMPL does out of the box; it
//                can clip a blocked cell's corner between two samples);
//  - one GogValidityChecker counts every validity evaluation, whichever planner asks; the grid
//    planner adds its own lattice checks to the same counter.
// Lattice state c maps to the continuous cell centre c + 0.5.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "hpcplan/env/gog.hpp"

namespace hpcplan::sampling {

class GogValidityChecker : public ompl::base::StateValidityChecker {
 public:
  GogValidityChecker(const ompl::base::SpaceInformationPtr& si,
                     std::shared_ptr<const GogField> field);

  bool isValid(const ompl::base::State* state) const override;

  // The lattice cell of a point inside the bounds (no counting); used by the grid planner and
  // by re-validation.
  std::vector<int> cell_of(const ompl::base::State* state) const;
  bool point_is_free(const double* x) const;  // the test isValid counts, without counting

  std::uint64_t checks() const { return checks_.load(std::memory_order_relaxed); }
  void add_checks(std::uint64_t n) const { checks_.fetch_add(n, std::memory_order_relaxed); }
  void reset_checks() const { checks_.store(0, std::memory_order_relaxed); }

  const GogField& field() const { return *field_; }

 private:
  std::shared_ptr<const GogField> field_;
  int dims_;
  int last_cell_;
  std::vector<const std::uint8_t*> levels_;
  mutable std::atomic<std::uint64_t> checks_{0};
};

enum class MotionCheck { exact, discrete };
MotionCheck parse_motion_check(std::string_view name);  // InputError if unknown

struct GogWorld {
  std::shared_ptr<const GogField> field;
  ompl::base::StateSpacePtr space;
  ompl::base::SpaceInformationPtr si;
  std::shared_ptr<GogValidityChecker> checker;
  double resolution_cells = 0.0;
  MotionCheck motion = MotionCheck::exact;
};

// Builds and sets up the space information; InputError for a resolution outside (0, 1].
GogWorld make_gog_world(std::shared_ptr<const GogField> field, double resolution_cells,
                        MotionCheck motion = MotionCheck::exact);

// Continuous centre of a lattice cell, written into `state`.
void cell_centre(const std::vector<int>& cell, ompl::base::State* state);

// Re-validates a path with direct field look-ups, independently of the planners: every
// waypoint must be valid, and every segment is sampled every 0.01 cell widths (exact motions,
// which guarantee every point valid) or checked by the world's own motion validator (discrete
// motions: a sampled validator only answers for its own samples). Returns the index of the
// first bad waypoint or segment, or -1 when the path is valid.
long first_invalid_step(const GogWorld& world, const std::vector<std::vector<double>>& path);

}  // namespace hpcplan::sampling
