#include "hpcplan/sampling/gog_world.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sampling/gog_motion_validator.hpp"

namespace ob = ompl::base;

namespace hpcplan::sampling {

GogValidityChecker::GogValidityChecker(const ob::SpaceInformationPtr& si,
                                       std::shared_ptr<const GogField> field)
    : ob::StateValidityChecker(si),
      field_(std::move(field)),
      dims_(field_->dims()),
      last_cell_(field_->extent() - 1) {
  for (int a = 0; a < dims_; ++a) levels_.push_back(field_->level_table(a));
}

bool GogValidityChecker::point_is_free(const double* x) const {
  int sum = 0;
  const double upper = static_cast<double>(field_->extent());
  for (int a = 0; a < dims_; ++a) {
    if (!(x[a] >= 0.0 && x[a] <= upper)) return false;  // outside the box (or NaN)
    const int c = std::min(static_cast<int>(x[a]), last_cell_);
    sum += levels_[a][c];
  }
  return sum < field_->threshold();
}

bool GogValidityChecker::isValid(const ob::State* state) const {
  checks_.fetch_add(1, std::memory_order_relaxed);
  return point_is_free(state->as<ob::RealVectorStateSpace::StateType>()->values);
}

std::vector<int> GogValidityChecker::cell_of(const ob::State* state) const {
  const double* x = state->as<ob::RealVectorStateSpace::StateType>()->values;
  std::vector<int> cell(dims_);
  for (int a = 0; a < dims_; ++a)
    cell[a] = std::clamp(static_cast<int>(std::floor(x[a])), 0, last_cell_);
  return cell;
}

MotionCheck parse_motion_check(std::string_view name) {
  if (name == "exact") return MotionCheck::exact;
  if (name == "discrete") return MotionCheck::discrete;
  throw InputError("unknown --motion '" + std::string(name) + "' (expected exact or discrete)");
}

GogWorld make_gog_world(std::shared_ptr<const GogField> field, double resolution_cells,
                        MotionCheck motion) {
  if (!(resolution_cells > 0.0 && resolution_cells <= 1.0))
    throw InputError("--resolution must be in (0, 1] cell widths, got " +
                     std::to_string(resolution_cells));
  GogWorld w;
  w.field = field;
  w.resolution_cells = resolution_cells;
  w.motion = motion;
  const int d = field->dims();
  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(d));
  space->setBounds(0.0, static_cast<double>(field->extent()));
  w.space = space;
  w.si = std::make_shared<ob::SpaceInformation>(space);
  w.checker = std::make_shared<GogValidityChecker>(w.si, field);
  w.si->setStateValidityChecker(w.checker);
  // OMPL's resolution is a fraction of the space's longest extent (its diagonal).
  // (It also sets how finely some planners interpolate, so it is set in both modes.)
  w.si->setStateValidityCheckingResolution(resolution_cells / space->getMaximumExtent());
  if (motion == MotionCheck::exact)
    w.si->setMotionValidator(std::make_shared<GogMotionValidator>(w.si, w.checker));
  w.si->setup();
  return w;
}

void cell_centre(const std::vector<int>& cell, ob::State* state) {
  double* x = state->as<ob::RealVectorStateSpace::StateType>()->values;
  for (std::size_t a = 0; a < cell.size(); ++a) x[a] = cell[a] + 0.5;
}

long first_invalid_step(const GogWorld& world, const std::vector<std::vector<double>>& path) {
  const GogValidityChecker& c = *world.checker;
  const double spacing = 0.01;
  ompl::base::ScopedState<> sa(world.space), sb(world.space);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!c.point_is_free(path[i].data())) return static_cast<long>(i);
    if (i == 0) continue;
    const auto& a = path[i - 1];
    const auto& b = path[i];
    if (world.motion == MotionCheck::discrete) {
      for (std::size_t k = 0; k < a.size(); ++k) {
        sa[k] = a[k];
        sb[k] = b[k];
      }
      if (!world.si->checkMotion(sa.get(), sb.get())) return static_cast<long>(i);
      continue;
    }
    double len2 = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) len2 += (b[k] - a[k]) * (b[k] - a[k]);
    const long steps = static_cast<long>(std::ceil(std::sqrt(len2) / spacing));
    std::vector<double> p(a.size());
    for (long s = 1; s < steps; ++s) {
      const double t = static_cast<double>(s) / static_cast<double>(steps);
      for (std::size_t k = 0; k < a.size(); ++k) p[k] = a[k] + t * (b[k] - a[k]);
      if (!c.point_is_free(p.data())) return static_cast<long>(i);
    }
  }
  return -1;
}

}  // namespace hpcplan::sampling
