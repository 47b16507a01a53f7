#pragma once
// SPH smoothing kernels as small values: built once from their support radius, then evaluated
// from a squared distance (w) or a distance (the gradient's radial factor, the Laplacian), so
// that the hot loops do no divisions by h.
//
// The gradient is written as grad_i W(r_ij) = dwdr(r) * r_ij / r with r_ij = x_i - x_j and
// dwdr <= 0 inside the support; swapping i and j flips r_ij and so the gradient's sign exactly,
// which is what makes the symmetric pair forces cancel (momentum conservation).
//
// Müller et al. 2003 (the seed preset): poly6 for density, spiky for the pressure gradient,
// the viscosity kernel's Laplacian for viscosity; all with support radius H.
// Wendland C2 (the water preset): smoothing length h, support radius 2h.
//
// C++17 and HPCPLAN_HD: both backends evaluate these very functions (see physics.hpp).
#include "hpcplan/core/portable.hpp"

namespace hpcplan::sph {

// pi to double precision (std::numbers is C++20; nvcc compiles this header as C++17).
inline constexpr double kPi = 3.14159265358979323846;

struct Poly6Kernel {
  double support = 0, support2 = 0, norm = 0;
  HPCPLAN_HD explicit Poly6Kernel(double h = 1.0)
      : support(h), support2(h * h), norm(315.0 / (64.0 * kPi * pow9(h))) {}
  HPCPLAN_HD double w(double r2) const {
    if (r2 >= support2) return 0.0;
    const double d = support2 - r2;
    return norm * d * d * d;
  }
  HPCPLAN_HD static double pow9(double h) {
    const double h3 = h * h * h;
    return h3 * h3 * h3;
  }
};

struct SpikyKernel {
  double support = 0, norm = 0;
  HPCPLAN_HD explicit SpikyKernel(double h = 1.0)
      : support(h), norm(15.0 / (kPi * h * h * h * h * h * h)) {}
  HPCPLAN_HD double w(double r) const {
    if (r >= support) return 0.0;
    const double d = support - r;
    return norm * d * d * d;
  }
  HPCPLAN_HD double dwdr(double r) const {
    if (r >= support) return 0.0;
    const double d = support - r;
    return -3.0 * norm * d * d;
  }
};

// The viscosity kernel of Müller et al.: W = 15/(2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1),
// whose Laplacian 45/(pi h^6) (h - r) is positive everywhere inside the support.
struct ViscosityKernel {
  double support = 0, lap_norm = 0, w_norm = 0;
  HPCPLAN_HD explicit ViscosityKernel(double h = 1.0)
      : support(h),
        lap_norm(45.0 / (kPi * h * h * h * h * h * h)),
        w_norm(15.0 / (2.0 * kPi * h * h * h)) {}
  HPCPLAN_HD double w(double r) const {
    if (r >= support || r <= 0.0) return 0.0;
    const double q = r / support;
    return w_norm * (-0.5 * q * q * q + q * q + 0.5 / q - 1.0);
  }
  HPCPLAN_HD double laplacian(double r) const {
    return r >= support ? 0.0 : lap_norm * (support - r);
  }
};

// Wendland C2 in 3D: W = 21/(16 pi h^3) (1 - q/2)^4 (2q + 1), q = r/h in [0, 2].
struct WendlandC2Kernel {
  double h = 0, support = 0, support2 = 0, norm = 0, inv_h = 0;
  HPCPLAN_HD explicit WendlandC2Kernel(double smoothing_length = 1.0)
      : h(smoothing_length),
        support(2.0 * smoothing_length),
        support2(4.0 * smoothing_length * smoothing_length),
        norm(21.0 / (16.0 * kPi * h * h * h)),
        inv_h(1.0 / smoothing_length) {}
  HPCPLAN_HD double w(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    const double a2 = a * a;
    return norm * a2 * a2 * (2.0 * q + 1.0);
  }
  HPCPLAN_HD double dwdr(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return -5.0 * norm * inv_h * q * a * a * a;
  }
};

}  // namespace hpcplan::sph
