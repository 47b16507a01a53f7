#pragma once
// Pressure from density, for both presets, on the host and the GPU (see physics.hpp).
#include <cmath>

#include "hpcplan/core/portable.hpp"
#include "hpcplan/sph/physics/params.hpp"

namespace hpcplan::sph {

// max(lo, x) as std::max(lo, x) evaluates it (lo when x is NaN), callable on a GPU.
HPCPLAN_HD inline double at_least(double lo, double x) {
  return lo < x ? x : lo;
}

// The seed preset: p = k max(0, rho - rho0) (Müller et al.'s ideal gas, clamped so that a
// sparse particle gas never pulls itself together).
HPCPLAN_HD inline double seed_pressure(const FluidParams& f, double rho) {
  return f.gas_constant * at_least(0.0, rho - f.rest_density);
}

// The water preset: Tait's p = B ((rho / rho0)^7 - 1), B = rho0 c0^2 / 7, clamped at zero
// (no tension at the free surface).
HPCPLAN_HD inline double tait_pressure(const FluidParams& f, double rho) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  const double r = rho / f.rest_density;
  const double r2 = r * r;
  return at_least(0.0, b * (r2 * r2 * r2 * r - 1.0));
}

// Its inverse: the density at which Tait's equation gives pressure p >= 0.
HPCPLAN_HD inline double tait_density(const FluidParams& f, double p) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  return f.rest_density * pow(p / b + 1.0, 1.0 / 7.0);
}

}  // namespace hpcplan::sph
