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

double water_height(const FluidState& s, double x, double y, double density_fraction) {
  const Particles& p = s.particles;
  const FluidParams& f = s.params;
  const WendlandC2Kernel kernel(f.smoothing_length);
  const double reach = kernel.support, floor = s.domain.lo[2];
  // The fluid particles whose kernel reaches the line.
  std::vector<std::size_t> near;
  double top = floor;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i]) continue;
    const double dx = x - p.x[i], dy = y - p.y[i];
    if (dx * dx + dy * dy < reach * reach) {
      near.push_back(i);
      top = std::max(top, p.z[i] + reach);
    }
  }
  auto density_at = [&](double z) {
    double rho = 0.0;
    for (const std::size_t j : near) {
      const double dx = x - p.x[j], dy = y - p.y[j];
      for (const double zj : {p.z[j], 2.0 * floor - p.z[j]}) {
        const double dz = z - zj;
        rho += f.particle_mass * kernel.w(std::sqrt(dx * dx + dy * dy + dz * dz));
      }
    }
    return rho;
  };
  const double threshold = density_fraction * f.rest_density, step = f.particle_spacing / 8.0;
  double z = top, above = density_at(z);
  while (above < threshold && z > floor) {
    const double upper = above, z_upper = z;  // the sample above the next one
    z = std::max(floor, z - step);
    above = density_at(z);
    if (above >= threshold) {  // crossed between z and z_upper (less than a step at the floor)
      const double frac = (threshold - above) / (upper - above);
      return z - floor + frac * (z_upper - z);
    }
  }
  return above >= threshold ? top - floor : 0.0;
}

Probes probes_for(Scenario scenario) {
  Probes p;
  p.scenario = scenario;
  if (scenario == Scenario::dambreak) p.columns = {"T", "Z"};
  if (scenario == Scenario::marin) {
    p.columns = {"t"};
    for (const Gauge& g : kMarinGauges) p.columns.emplace_back(g.name);
    p.interval = 0.005;  // the experiment's record is every 1 ms; its features last 0.05 s+
  }
  return p;
}

void record_probes(const FluidState& s, Probes& probes) {
  if (probes.columns.empty()) return;
  if (probes.scenario == Scenario::dambreak) {
    const SurgeFront f = dam_break_front(s);
    probes.rows.push_back({f.t, f.z});
    return;
  }
  if (s.time < static_cast<double>(probes.rows.size()) * probes.interval) return;
  std::vector<double> row{s.time};
  const double y = 0.5 * (s.domain.lo[1] + s.domain.hi[1]);
  for (const Gauge& g : kMarinGauges) row.push_back(water_height(s, g.x, y));
  probes.rows.push_back(std::move(row));
}

}  // namespace hpcplan::sph
