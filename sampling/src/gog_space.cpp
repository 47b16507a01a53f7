#include "hpcplan/sampling/gog_space.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <ompl/base/ScopedState.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/gog_world.hpp"

namespace ob = ompl::base;

namespace hpcplan::sampling {

namespace {

template <int D>
GogSpace make_for(std::shared_ptr<const GogField> field, double resolution_cells,
                  MotionCheck motion) {
  auto world = std::make_shared<const env::GogWorld<D>>(field);
  GogSpace s;
  s.field = std::move(field);
  s.checks = &world->check_counter();
  s.resolution_cells = resolution_cells;
  s.motion = motion;
  // Cells are one unit wide, so the resolution in cells is one in state-space units.
  s.si = make_space_information(std::move(world), SpaceOptions{motion, resolution_cells});
  s.space = s.si->getStateSpace();
  return s;
}

}  // namespace

GogSpace make_gog_space(std::shared_ptr<const GogField> field, double resolution_cells,
                        MotionCheck motion) {
  if (!(resolution_cells > 0.0 && resolution_cells <= 1.0))
    throw InputError("--resolution must be in (0, 1] cell widths, got " +
                     std::to_string(resolution_cells));
  const int dims = field->dims();
  GogSpace space;
  bool made = false;
  // The world's dimension is a template parameter: pick the instance for this field.
  [&]<int... I>(std::integer_sequence<int, I...>) {
    ((dims == I + 1 ? (space = make_for<I + 1>(field, resolution_cells, motion), made = true)
                    : false) ||
     ...);
  }
  (std::make_integer_sequence<int, env::kGogMaxDims>{});
  if (!made) throw InputError("a GOG space has 1 to 16 dimensions, got " + std::to_string(dims));
  return space;
}

void cell_centre(const std::vector<int>& cell, ob::State* state) {
  double* x = state->as<ob::RealVectorStateSpace::StateType>()->values;
  for (std::size_t a = 0; a < cell.size(); ++a) x[a] = cell[a] + 0.5;
}

long first_invalid_step(const GogSpace& space, const std::vector<std::vector<double>>& path) {
  const GogField& field = *space.field;
  const double spacing = 0.01;
  ob::ScopedState<> sa(space.space), sb(space.space);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!env::gog_point_free(field, path[i].data())) return static_cast<long>(i);
    if (i == 0) continue;
    const auto& a = path[i - 1];
    const auto& b = path[i];
    if (space.motion == MotionCheck::discrete) {
      for (std::size_t k = 0; k < a.size(); ++k) {
        sa[k] = a[k];
        sb[k] = b[k];
      }
      if (!space.si->checkMotion(sa.get(), sb.get())) return static_cast<long>(i);
      continue;
    }
    double len2 = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) len2 += (b[k] - a[k]) * (b[k] - a[k]);
    const long steps = static_cast<long>(std::ceil(std::sqrt(len2) / spacing));
    std::vector<double> p(a.size());
    for (long s = 1; s < steps; ++s) {
      const double t = static_cast<double>(s) / static_cast<double>(steps);
      for (std::size_t k = 0; k < a.size(); ++k) p[k] = a[k] + t * (b[k] - a[k]);
      if (!env::gog_point_free(field, p.data())) return static_cast<long>(i);
    }
  }
  return -1;
}

}  // namespace hpcplan::sampling
