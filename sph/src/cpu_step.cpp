// The CPU backend. Phases (each an OpenMP parallel for over particles, each particle writing
// only its own entries, so no atomics and a result independent of the thread count):
//   seed:  grid -> density (poly6) and pressure -> accelerations (spiky pressure, viscosity
//          Laplacian, gravity) -> integration -> boundaries;
//   water: grid -> density (continuity equation, stepped) and pressure (Tait) -> wall pressure
//          (Adami et al. 2012: extrapolated from the fluid with the hydrostatic term) ->
//          accelerations (pressure, Monaghan viscosity among fluid particles: free-slip walls,
//          gravity) -> integration -> boundaries.
// Integration is symplectic Euler: velocity, then position with the new velocity (and, for
// water, density before the velocity).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/sph/boundaries.hpp"
#include "hpcplan/sph/kernels.hpp"
#include "hpcplan/sph/neighbour_lists.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

namespace {

using Index = std::ptrdiff_t;

double tait_pressure(const FluidParams& f, double rho) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  const double r = rho / f.rest_density;
  const double r2 = r * r;
  return std::max(0.0, b * (r2 * r2 * r2 * r - 1.0));
}

double tait_density(const FluidParams& f, double p) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  return f.rest_density * std::pow(p / b + 1.0, 1.0 / 7.0);
}

void seed_forces(FluidState& s, const NeighbourLists& lists) {
  Particles& p = s.particles;
  const FluidParams& f = s.params;
  const Poly6Kernel poly6(f.support);
  const SpikyKernel spiky(f.support);
  const ViscosityKernel visc(f.support);
  const Index n = static_cast<Index>(p.size());
  const double m = f.particle_mass;
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    double rho = m * poly6.w(0.0);  // itself
    std::uint32_t count = 0;
    lists.for_each(static_cast<std::size_t>(i), s.grid, p,
                   [&](std::uint32_t, double, double, double, double r2) {
                     rho += m * poly6.w(r2);
                     ++count;
                   });
    p.rho[i] = rho;
    p.p[i] = f.gas_constant * std::max(0.0, rho - f.rest_density);
    p.neighbours[i] = count;
  }
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const double pi = p.p[i];
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    double fx = 0.0, fy = 0.0, fz = 0.0;
    lists.for_each(static_cast<std::size_t>(i), s.grid, p,
                   [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                     const double r = std::sqrt(r2);
                     const double inv_rho_j = 1.0 / p.rho[j];
                     // Pressure: -m (p_i + p_j) / (2 rho_j) grad W_spiky; undefined direction at r
                     // = 0.
                     if (r > 0.0 && (pi > 0.0 || p.p[j] > 0.0)) {
                       const double c = -m * 0.5 * (pi + p.p[j]) * inv_rho_j * spiky.dwdr(r) / r;
                       fx += c * dx, fy += c * dy, fz += c * dz;
                     }
                     // Viscosity: mu m (v_j - v_i) / rho_j lap W.
                     const double c = f.viscosity * m * inv_rho_j * visc.laplacian(r);
                     fx += c * (p.vx[j] - vxi), fy += c * (p.vy[j] - vyi),
                         fz += c * (p.vz[j] - vzi);
                   });
    // Forces per unit volume divided by the density: accelerations. Gravity is an
    // acceleration (not divided by the density).
    const double inv_rho = 1.0 / p.rho[i];
    p.ax[i] = fx * inv_rho + f.gravity[0];
    p.ay[i] = fy * inv_rho + f.gravity[1];
    p.az[i] = fz * inv_rho + f.gravity[2];
  }
}

void water_forces(FluidState& s, const NeighbourLists& lists, double dt) {
  Particles& p = s.particles;
  const FluidParams& f = s.params;
  const WendlandC2Kernel kernel(f.smoothing_length);
  const Index n = static_cast<Index>(p.size());
  const double m = f.particle_mass;
  const double h = f.smoothing_length;
  const double eta2 = 0.01 * h * h;
  const double visc = f.alpha * f.sound_speed;  // Monaghan: Pi = -alpha c0 mu / rho_mean
  // Density first, from the velocities of step n (walls at rest), then the accelerations from
  // the new densities: the acoustic pair (density, velocity) is stepped symplectically. Both
  // explicit from step n would be forward Euler for sound waves, which grow without bound.
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    if (p.wall[i]) continue;
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    double drho = 0.0;
    lists.for_each(static_cast<std::size_t>(i), s.grid, p,
                   [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                     if (r2 == 0.0) return;
                     const double r = std::sqrt(r2);
                     const bool wall = p.wall[j];
                     const double ux = vxi - (wall ? 0.0 : p.vx[j]),
                                  uy = vyi - (wall ? 0.0 : p.vy[j]),
                                  uz = vzi - (wall ? 0.0 : p.vz[j]);
                     drho += m * (ux * dx + uy * dy + uz * dz) * kernel.dwdr(r) / r;
                   });
    p.drho[i] = drho;
    p.rho[i] += dt * drho;
    p.p[i] = tait_pressure(f, p.rho[i]);
  }
  // Wall particles: the fluid's pressure extrapolated, plus the hydrostatic difference
  // g . (x_wall - x_fluid) (static walls have no acceleration of their own). Walls with no
  // fluid in reach (most of a tall tank's sides) only reset.
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    if (!p.wall[i]) continue;
    if (lists.count(static_cast<std::size_t>(i)) == 0) {
      p.p[i] = 0.0;
      p.rho[i] = f.rest_density;
      p.neighbours[i] = 0;
      continue;
    }
    double sum_w = 0.0, sum_pw = 0.0, sum_rho_r = 0.0;
    std::uint32_t count = 0;
    lists.for_each(static_cast<std::size_t>(i), s.grid, p,
                   [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                     if (p.wall[j]) return;
                     const double w = kernel.w(std::sqrt(r2));
                     sum_w += w;
                     sum_pw += p.p[j] * w;
                     sum_rho_r +=
                         p.rho[j] * w * (f.gravity[0] * dx + f.gravity[1] * dy + f.gravity[2] * dz);
                     ++count;
                   });
    const double pw = sum_w > 0.0 ? std::max(0.0, (sum_pw + sum_rho_r) / sum_w) : 0.0;
    p.p[i] = pw;
    p.rho[i] = tait_density(f, pw);
    p.neighbours[i] = count;
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    if (p.wall[i]) continue;
    const double rho_i = p.rho[i];
    const double pi_term = p.p[i] / (rho_i * rho_i);
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    double ax = 0.0, ay = 0.0, az = 0.0;
    std::uint32_t count = 0;
    lists.for_each(static_cast<std::size_t>(i), s.grid, p,
                   [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                     if (r2 == 0.0)
                       return;  // itself (no two particles coincide in a pressured fluid)
                     ++count;
                     const double r = std::sqrt(r2);
                     const double g = kernel.dwdr(r) / r;  // grad_i W = g * (dx, dy, dz)
                     const double rho_j = p.rho[j];
                     double c = pi_term + p.p[j] / (rho_j * rho_j);
                     if (!p.wall[j]) {  // free-slip walls: no viscosity against them
                       const double vr =
                           (vxi - p.vx[j]) * dx + (vyi - p.vy[j]) * dy + (vzi - p.vz[j]) * dz;
                       if (vr < 0.0) c -= visc * (h * vr / (r2 + eta2)) / (0.5 * (rho_i + rho_j));
                     }
                     c *= -m * g;
                     ax += c * dx, ay += c * dy, az += c * dz;
                   });
    p.ax[i] = ax + f.gravity[0];
    p.ay[i] = ay + f.gravity[1];
    p.az[i] = az + f.gravity[2];
    p.neighbours[i] = count;
  }
}

void integrate(FluidState& s, double dt) {
  Particles& p = s.particles;
  const Index n = static_cast<Index>(p.size());
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (p.wall[i]) continue;
    p.vx[i] += dt * p.ax[i];
    p.vy[i] += dt * p.ay[i];
    p.vz[i] += dt * p.az[i];
    p.x[i] += dt * p.vx[i];
    p.y[i] += dt * p.vy[i];
    p.z[i] += dt * p.vz[i];
    keep_out_of_obstacles_fast(s.domain, s.boxes, s.params.restitution, p,
                               static_cast<std::size_t>(i));
  }
}

class CpuBackend final : public StepBackend {
 public:
  std::string name() const override { return "cpu"; }

  double stable_dt(const FluidState& s) override {
    const Particles& p = s.particles;
    const Index n = static_cast<Index>(p.size());
    double v2 = 0.0, a2 = 0.0;
    std::uint32_t most_neighbours = 0;
    bool compressed = false;
#pragma omp parallel for schedule(static) reduction(max                        \
                                                    : v2, a2, most_neighbours) \
    reduction(||                                                               \
              : compressed)
    for (Index i = 0; i < n; ++i) {
      if (p.wall[i]) continue;
      v2 = std::max(v2, p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      a2 = std::max(a2, p.ax[i] * p.ax[i] + p.ay[i] * p.ay[i] + p.az[i] * p.az[i]);
      most_neighbours = std::max(most_neighbours, p.neighbours[i]);
      compressed = compressed || p.rho[i] > s.params.rest_density;
    }
    return stable_dt_from(s, {v2, a2, most_neighbours, compressed});
  }

  SubstepReport substep(FluidState& s, double dt) override {
    SubstepReport report;
    for (MovingBox& b : s.boxes) move_box(s.domain, b, dt);
    const Stopwatch clock;
    s.grid.build(s.particles);
    if (s.params.reorder_every > 0 &&
        s.substeps % static_cast<std::uint64_t>(s.params.reorder_every) == 0)
      s.grid.sort_particles(s.particles);
    const Particles& p = s.particles;
    const std::uint32_t capacity = list_capacity(s.params.preset);
    if (lists_.capacity() != capacity) lists_ = NeighbourLists(capacity);
    if (s.params.preset == Preset::seed) {
      lists_.build(s.grid, p, [](std::size_t) { return true; });
      report.grid_ms = clock.milliseconds();
      seed_forces(s, lists_);
    } else {
      // Lists for the fluid and for the walls with fluid in reach (most of a tall tank's sides
      // never see any), read by the three passes of the substep.
      s.grid.mark_cells_of(p, 0);
      lists_.build(s.grid, p, [&](std::size_t i) {
        return !p.wall[i] || s.grid.near_marked(p.x[i], p.y[i], p.z[i]);
      });
      report.grid_ms = clock.milliseconds();
      water_forces(s, lists_, dt);
    }
    integrate(s, dt);
    s.time += dt;
    ++s.substeps;
    return report;
  }

 private:
  NeighbourLists lists_;
};

}  // namespace

double stable_dt_from(const FluidState& s, const StepLimits& limits) {
  const FluidParams& f = s.params;
  double v2 = limits.max_speed2, a2 = limits.max_acceleration2;
  for (const MovingBox& b : s.boxes) v2 = std::max(v2, dot(b.velocity, b.velocity));
  // The signal speed: the flow plus sound. The seed's EOS clamps at the rest density, so
  // sound (sqrt(k)) only travels where some particle is compressed.
  double c = f.sound_speed;
  if (f.preset == Preset::seed) c = limits.compressed ? std::sqrt(f.gas_constant) : 0.0;
  const double h = f.preset == Preset::water ? f.smoothing_length : f.support;
  a2 = std::max(a2, dot(f.gravity, f.gravity));
  double dt = f.frame_dt;
  const double speed = c + std::sqrt(v2);
  if (speed > 0.0) dt = std::min(dt, f.cfl * h / speed);
  if (a2 > 0.0) dt = std::min(dt, f.cfl * std::sqrt(h / std::sqrt(a2)));
  if (f.preset == Preset::seed && f.viscosity > 0.0) {
    // Müller's viscous acceleration relaxes a velocity difference at a rate of at most
    // mu m lap W(0) / rho^2 per neighbour, rho no less than a particle's own density: keep
    // the explicit update well inside its stability limit.
    const double rho_min = f.particle_mass * Poly6Kernel(f.support).w(0.0);
    const double rate = f.viscosity * f.particle_mass * ViscosityKernel(f.support).laplacian(0.0) /
                        (rho_min * rho_min) * std::max<std::uint32_t>(1, limits.most_neighbours);
    dt = std::min(dt, 0.5 / rate);
  }
  return dt;
}

std::uint32_t list_capacity(Preset preset) {
  // A packed water particle has ~75 neighbours within 2.6 dx, the seed's gas a handful; more
  // spill over to the grid (slower, still exact).
  return preset == Preset::water ? 96 : 16;
}

std::unique_ptr<StepBackend> make_cpu_backend() {
  return std::make_unique<CpuBackend>();
}

}  // namespace hpcplan::sph
