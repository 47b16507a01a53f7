#include "hpcplan/sph/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "hpcplan/sph/kernels.hpp"
#include "hpcplan/sph/presets.hpp"

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

SurgeFront dam_break_front(const FluidState& s, double density_fraction) {
  const Particles& p = s.particles;
  const FluidParams& f = s.params;
  const WendlandC2Kernel kernel(f.smoothing_length);
  const double reach = kernel.support, dx = f.particle_spacing;
  const double y_lo = s.domain.lo[1], y_hi = s.domain.hi[1], floor = s.domain.lo[2];
  const double y0 = 0.5 * (y_lo + y_hi), z0 = floor + 0.5 * dx;
  // The fluid particles whose kernel, or a mirror image's, reaches the line, by x.
  std::vector<std::pair<double, std::size_t>> near;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!p.wall[i] && p.z[i] < z0 + reach) near.emplace_back(p.x[i], i);
  std::sort(near.begin(), near.end());
  const double a = kDamBreakColumn, g = -f.gravity[2];
  const double t = s.time * std::sqrt(2.0 * g / a);
  if (near.empty()) return {t, 0.0};
  auto density_at = [&](double x) {
    double rho = 0.0;
    auto first =
        std::lower_bound(near.begin(), near.end(), std::make_pair(x - reach, std::size_t{0}));
    for (auto it = first; it != near.end() && it->first < x + reach; ++it) {
      const std::size_t j = it->second;
      const double ddx = x - p.x[j];
      for (const double yj : {p.y[j], 2.0 * y_lo - p.y[j], 2.0 * y_hi - p.y[j]})
        for (const double zj : {p.z[j], 2.0 * floor - p.z[j]}) {
          const double dy = y0 - yj, dz = z0 - zj;
          rho += f.particle_mass * kernel.w(std::sqrt(ddx * ddx + dy * dy + dz * dz));
        }
    }
    return rho;
  };
  const double threshold = density_fraction * f.rest_density, step = dx / 8.0;
  double x = near.back().first + reach, above = density_at(x);
  while (above < threshold && x > s.domain.lo[0]) {
    const double below = above;
    x -= step;
    above = density_at(x);
    if (above >= threshold) {  // crossed between x and x + step
      const double frac = (threshold - above) / (below - above);
      return {t, (x + frac * step) / a};
    }
  }
  return {t, x / a};
}

}  // namespace hpcplan::sph
