#pragma once
// The fluid's physics, phase by phase, written once for every backend (see physics.hpp).
//
// A phase is a small value built on the host from the parameters (its kernels and constants
// precomputed) and called once per particle: phase(step, i, neighbours), where
// neighbours(fn) calls fn(j, dx, dy, dz, r2) for every particle j != i within the support,
// (dx, dy, dz) = x_i - x_j. A phase writes only particle i's entries, so a backend may run
// the particles in any order and on any number of threads: the CPU backend calls it inside an
// OpenMP loop over neighbour lists, the CUDA backend inside a kernel over cell ranges.
// Sums run in the backend's neighbour order, so the two backends agree to round-off, and
// each backend is bitwise independent of its thread count.
//
// The gradient is grad_i W(r_ij) = dwdr(r) r_ij / r with r_ij = x_i - x_j (kernels.hpp).
#include <cstddef>
#include <cstdint>

#include "hpcplan/core/portable.hpp"
#include "hpcplan/sph/kernels.hpp"
#include "hpcplan/sph/particle_fields.hpp"
#include "hpcplan/sph/physics/equation_of_state.hpp"
#include "hpcplan/sph/physics/params.hpp"
#include "hpcplan/sph/physics/push_out.hpp"

namespace hpcplan::sph {

// What every phase of one substep sees besides its own constants.
struct StepView {
  ParticleView a;
  double dt = 0.0;
  Box3 domain{};
  const MovingBox* boxes = nullptr;  // the obstacle boxes at the substep's end
  int box_count = 0;
};

// ---- seed preset (Müller et al. 2003) --------------------------------------------------------

// Density by poly6 (itself included), the clamped gas pressure, the neighbour count.
struct SeedDensity {
  Poly6Kernel poly6;
  FluidParams f;
  explicit SeedDensity(const FluidParams& params) : poly6(params.support), f(params) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&& neighbours) const {
    const double m = f.particle_mass;
    double rho = m * poly6.w(0.0);
    std::uint32_t count = 0;
    neighbours([&](std::uint32_t, double, double, double, double r2) {
      rho += m * poly6.w(r2);
      ++count;
    });
    s.a.rho[i] = rho;
    s.a.p[i] = seed_pressure(f, rho);
    s.a.neighbours[i] = count;
  }
};

// Pressure -m (p_i + p_j) / (2 rho_j) grad W_spiky, viscosity mu m (v_j - v_i) / rho_j lap W,
// both per unit volume and divided by rho_i; gravity is an acceleration.
struct SeedAcceleration {
  SpikyKernel spiky;
  ViscosityKernel visc;
  FluidParams f;
  explicit SeedAcceleration(const FluidParams& params)
      : spiky(params.support), visc(params.support), f(params) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&& neighbours) const {
    const ParticleView& a = s.a;
    const double m = f.particle_mass;
    const double pi = a.p[i];
    const double vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i];
    double fx = 0.0, fy = 0.0, fz = 0.0;
    neighbours([&](std::uint32_t j, double dx, double dy, double dz, double r2) {
      const double r = sqrt(r2);
      const double inv_rho_j = 1.0 / a.rho[j];
      // The spiky gradient's direction is undefined at r = 0.
      if (r > 0.0 && (pi > 0.0 || a.p[j] > 0.0)) {
        const double c = -m * 0.5 * (pi + a.p[j]) * inv_rho_j * spiky.dwdr(r) / r;
        fx += c * dx, fy += c * dy, fz += c * dz;
      }
      const double c = f.viscosity * m * inv_rho_j * visc.laplacian(r);
      fx += c * (a.vx[j] - vxi), fy += c * (a.vy[j] - vyi), fz += c * (a.vz[j] - vzi);
    });
    const double inv_rho = 1.0 / a.rho[i];
    a.ax[i] = fx * inv_rho + f.gravity[0];
    a.ay[i] = fy * inv_rho + f.gravity[1];
    a.az[i] = fz * inv_rho + f.gravity[2];
  }
};

// ---- water preset (weakly compressible, Wendland C2, Tait) -----------------------------------

// Fluid particles: the continuity equation's rate, plus delta-SPH's density diffusion among
// fluid particles: delta h c0 sum_j psi_ij . grad_i W V_j with psi_ij = 2 (rho_j - rho_i -
// rho^H_ji) (x_j - x_i) / r^2, where rho^H_ji, the hydrostatic density difference
// (Fourtakas et al. 2019), keeps the diffusion from flattening the hydrostatic profile; it is
// taken to first order, rho0^2 g (z_i - z_j) / (7 B) = rho0 g (z_i - z_j) / c0^2 (within a
// kernel's reach the next term is below 1e-3 of it; across a whole column, 2.5%). The
// rate only: the density is stepped in WaterDensityStep, after every rate is read (a particle
// reads its neighbours' densities here).
struct WaterContinuity {
  WendlandC2Kernel kernel;
  FluidParams f;
  double diffusion, hydrostatic;
  explicit WaterContinuity(const FluidParams& params)
      : kernel(params.smoothing_length),
        f(params),
        diffusion(params.delta * params.smoothing_length * params.sound_speed),
        hydrostatic(1.0 / (params.sound_speed * params.sound_speed)) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&& neighbours) const {
    const ParticleView& a = s.a;
    if (a.wall[i]) return;
    const double m = f.particle_mass;
    const double vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i], rho_i = a.rho[i];
    double drho = 0.0, spread = 0.0;
    neighbours([&](std::uint32_t j, double dx, double dy, double dz, double r2) {
      if (r2 == 0.0) return;
      const double r = sqrt(r2);
      const bool wall = a.wall[j];
      const double ux = vxi - (wall ? 0.0 : a.vx[j]), uy = vyi - (wall ? 0.0 : a.vy[j]),
                   uz = vzi - (wall ? 0.0 : a.vz[j]);
      const double g = kernel.dwdr(r) / r;  // grad_i W = g * (dx, dy, dz)
      drho += m * (ux * dx + uy * dy + uz * dz) * g;
      if (!wall && diffusion > 0.0) {
        // rho^H_ji = rho0 (-gravity . x_ij) / c0^2.
        const double rho_h = -(f.gravity[0] * dx + f.gravity[1] * dy + f.gravity[2] * dz) *
                             f.rest_density * hydrostatic;
        // psi_ij . grad_i W = 2 (drho_ji) (-x_ij . x_ij g) / r^2 = -2 drho_ji g.
        spread += -2.0 * (a.rho[j] - rho_i - rho_h) * g * m / a.rho[j];
      }
    });
    a.drho[i] = drho + diffusion * spread;
  }
};

// Fluid particles: the density stepped by its rate, and Tait's pressure from it.
struct WaterDensityStep {
  FluidParams f;
  explicit WaterDensityStep(const FluidParams& params) : f(params) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&&) const {
    const ParticleView& a = s.a;
    if (a.wall[i]) return;
    a.rho[i] += s.dt * a.drho[i];
    a.p[i] = tait_pressure(f, a.rho[i]);
  }
};

// Wall particles (Adami et al. 2012): the fluid's pressure extrapolated, plus the hydrostatic
// difference g . (x_wall - x_fluid) (static walls have no acceleration of their own). A wall
// with no fluid in reach rests.
struct WallPressure {
  WendlandC2Kernel kernel;
  FluidParams f;
  explicit WallPressure(const FluidParams& params) : kernel(params.smoothing_length), f(params) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&& neighbours) const {
    const ParticleView& a = s.a;
    if (!a.wall[i]) return;
    double sum_w = 0.0, sum_pw = 0.0, sum_rho_r = 0.0, sum_v[3] = {0.0, 0.0, 0.0};
    std::uint32_t count = 0;
    neighbours([&](std::uint32_t j, double dx, double dy, double dz, double r2) {
      if (a.wall[j]) return;
      const double w = kernel.w(sqrt(r2));
      sum_w += w;
      sum_pw += a.p[j] * w;
      sum_rho_r += a.rho[j] * w * (f.gravity[0] * dx + f.gravity[1] * dy + f.gravity[2] * dz);
      sum_v[0] += a.vx[j] * w, sum_v[1] += a.vy[j] * w, sum_v[2] += a.vz[j] * w;
      ++count;
    });
    const double pw = sum_w > 0.0 ? at_least(0.0, (sum_pw + sum_rho_r) / sum_w) : 0.0;
    a.p[i] = pw;
    a.rho[i] = count > 0 ? tait_density(f, pw) : f.rest_density;
    a.neighbours[i] = count;
    // No-slip: the wall (at rest) carries 2 * 0 - v~, v~ the fluid's interpolated velocity, so
    // that the velocity interpolated across the wall vanishes on it. (Only the viscous terms
    // read it; the continuity equation sees the wall's own velocity, zero.)
    const bool mirror = f.no_slip && a.wall[i] == kNoSlipWall && sum_w > 0.0;
    a.vx[i] = mirror ? -sum_v[0] / sum_w : 0.0;
    a.vy[i] = mirror ? -sum_v[1] / sum_w : 0.0;
    a.vz[i] = mirror ? -sum_v[2] / sum_w : 0.0;
  }
};

// Fluid particles: the symmetric pressure gradient, Monaghan's artificial viscosity
// (Pi = -alpha c0 mu / rho_mean) among fluid particles and, with no-slip walls, against the
// walls' mirrored velocities together with water's laminar viscosity; gravity. (With free-slip
// walls, nothing viscous acts against them.)
struct WaterAcceleration {
  WendlandC2Kernel kernel;
  FluidParams f;
  double eta2, visc, laminar;
  explicit WaterAcceleration(const FluidParams& params)
      : kernel(params.smoothing_length),
        f(params),
        eta2(0.01 * params.smoothing_length * params.smoothing_length),
        visc(params.alpha * params.sound_speed),
        laminar(params.kinematic_viscosity) {}
  template <class Neighbours>
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i, Neighbours&& neighbours) const {
    const ParticleView& a = s.a;
    if (a.wall[i]) return;
    const double m = f.particle_mass, h = f.smoothing_length;
    const double rho_i = a.rho[i];
    const double pi_term = a.p[i] / (rho_i * rho_i);
    const double vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i];
    double ax = 0.0, ay = 0.0, az = 0.0;
    std::uint32_t count = 0;
    neighbours([&](std::uint32_t j, double dx, double dy, double dz, double r2) {
      if (r2 == 0.0) return;  // no two particles coincide in a pressured fluid
      ++count;
      const double r = sqrt(r2);
      const double g = kernel.dwdr(r) / r;  // grad_i W = g * (dx, dy, dz)
      const double rho_j = a.rho[j];
      double c = pi_term + a.p[j] / (rho_j * rho_j);
      const bool wall = a.wall[j];
      // A no-slip wall's velocity is its mirror (WallPressure); a free-slip wall has none.
      if (!wall || (f.no_slip && a.wall[j] == kNoSlipWall)) {
        const double ux = vxi - a.vx[j], uy = vyi - a.vy[j], uz = vzi - a.vz[j];
        const double vr = ux * dx + uy * dy + uz * dz;
        if (vr < 0.0) c -= visc * (h * vr / (r2 + eta2)) / (0.5 * (rho_i + rho_j));
        if (wall && laminar > 0.0) {
          // Morris et al.: m (mu_i + mu_j) / (rho_i rho_j) (x_ij . grad W) / (r^2 + eta^2) u_ij
          // with mu = rho nu: m nu (rho_i + rho_j) / (rho_i rho_j) g r^2 / (r^2 + eta^2).
          const double k = laminar * m * (rho_i + rho_j) / (rho_i * rho_j) * g * r2 / (r2 + eta2);
          ax += k * ux, ay += k * uy, az += k * uz;
        }
      }
      c *= -m * g;
      ax += c * dx, ay += c * dy, az += c * dz;
    });
    a.ax[i] = ax + f.gravity[0];
    a.ay[i] = ay + f.gravity[1];
    a.az[i] = az + f.gravity[2];
    a.neighbours[i] = count;
  }
};

// ---- every preset ----------------------------------------------------------------------------

// Symplectic Euler (velocity, then position with the new velocity), then the hard
// constraints of push_out.hpp. Fluid particles only; walls never move.
struct Integrate {
  double restitution = 0.5;
  explicit Integrate(const FluidParams& params) : restitution(params.restitution) {}
  HPCPLAN_HD void operator()(const StepView& s, std::size_t i) const {
    const ParticleView& a = s.a;
    if (a.wall[i]) return;
    double v[3] = {a.vx[i] + s.dt * a.ax[i], a.vy[i] + s.dt * a.ay[i], a.vz[i] + s.dt * a.az[i]};
    double x[3] = {a.x[i] + s.dt * v[0], a.y[i] + s.dt * v[1], a.z[i] + s.dt * v[2]};
    push_out_of_obstacles(s.domain, s.boxes, s.box_count, restitution, x, v);
    a.vx[i] = v[0], a.vy[i] = v[1], a.vz[i] = v[2];
    a.x[i] = x[0], a.y[i] = x[1], a.z[i] = x[2];
  }
};

}  // namespace hpcplan::sph
