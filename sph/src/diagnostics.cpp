#include "hpcplan/sph/diagnostics.hpp"

#include "hpcplan/sph/presets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hpcplan::sph {

FluidSummary summarise(const FluidState& s) {
  const Particles& p = s.particles;
  const double m = s.params.particle_mass;
  FluidSummary r;
  double neighbours = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i]) continue;
    ++r.fluid;
    r.momentum = r.momentum + m * p.velocity(i);
    const double v2 = dot(p.velocity(i), p.velocity(i));
    r.kinetic_energy += 0.5 * m * v2;
    r.max_speed = std::max(r.max_speed, std::sqrt(v2));
    r.max_density_error = std::max(
        r.max_density_error, std::abs(p.rho[i] - s.params.rest_density) / s.params.rest_density);
    neighbours += p.neighbours[i];
    r.neighbours_max = std::max(r.neighbours_max, p.neighbours[i]);
  }
  r.mass = m * static_cast<double>(r.fluid);  // every particle carries the same mass
  if (r.fluid > 0) r.neighbours_mean = neighbours / static_cast<double>(r.fluid);
  return r;
}

SurgeFront dam_break_front(const FluidState& s) {
  const Particles& p = s.particles;
  double x = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!p.wall[i]) x = std::max(x, p.x[i]);
  const double a = kDamBreakColumn, g = -s.params.gravity[2];
  return {s.time * std::sqrt(2.0 * g / a), (x + 0.5 * s.params.particle_spacing) / a};
}

}  // namespace hpcplan::sph
