// The one physics source (sph/physics.hpp), function by function, against values worked out by
// hand from the formulas in the comments, on the CPU: the CUDA backend compiles these very
// functions, so a change that breaks one shows here whatever machine runs the suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/particles.hpp"
#include "hpcplan/sph/physics.hpp"

namespace hpcplan::sph {
namespace {

constexpr double kPiHand = 3.141592653589793;

TEST(SharedKernels, MatchHandValues) {
  // poly6, h = 0.5: 315 / (64 pi h^9) (h^2 - r^2)^3; at r^2 = 0.09: (0.16)^3 = 0.004096.
  const Poly6Kernel poly6(0.5);
  const double n6 = 315.0 / (64.0 * kPiHand * std::pow(0.5, 9));
  EXPECT_NEAR(poly6.w(0.09), n6 * 0.004096, 1e-12 * n6);
  EXPECT_EQ(poly6.w(0.25), 0.0);
  // spiky, h = 0.5: dW/dr = -45 / (pi h^6) (h - r)^2; at r = 0.2: (0.3)^2 = 0.09.
  const SpikyKernel spiky(0.5);
  const double n15 = 15.0 / (kPiHand * std::pow(0.5, 6));
  EXPECT_NEAR(spiky.w(0.2), n15 * 0.027, 1e-12 * n15);
  EXPECT_NEAR(spiky.dwdr(0.2), -3.0 * n15 * 0.09, 1e-12 * n15);
  // viscosity Laplacian: 45 / (pi h^6) (h - r).
  const ViscosityKernel visc(0.5);
  EXPECT_NEAR(visc.laplacian(0.2), 45.0 / (kPiHand * std::pow(0.5, 6)) * 0.3, 1e-9);
  // Wendland C2, h = 0.1 at q = 1: 21 / (16 pi h^3) (1/2)^4 (3) and dW/dr = -5 norm / h q (1/2)^3.
  const WendlandC2Kernel wendland(0.1);
  const double nw = 21.0 / (16.0 * kPiHand * 1e-3);
  EXPECT_NEAR(wendland.w(0.1), nw * 0.0625 * 3.0, 1e-12 * nw);
  EXPECT_NEAR(wendland.dwdr(0.1), -5.0 * nw / 0.1 * 0.125, 1e-12 * nw / 0.1);
  EXPECT_EQ(wendland.w(0.2), 0.0);
}

TEST(SharedEquationOfState, MatchesHandValues) {
  FluidParams f;
  f.rest_density = 1000.0;
  f.gas_constant = 2000.0;
  f.sound_speed = 10.0;
  EXPECT_EQ(seed_pressure(f, 1010.0), 20000.0);
  EXPECT_EQ(seed_pressure(f, 990.0), 0.0);  // clamped: a sparse gas does not pull
  // Tait: B = 1000 * 100 / 7; (1.01)^7 - 1 = 0.0721353...
  const double b = 1000.0 * 100.0 / 7.0;
  EXPECT_NEAR(tait_pressure(f, 1010.0), b * (std::pow(1.01, 7) - 1.0), 1e-9);
  EXPECT_EQ(tait_pressure(f, 999.0), 0.0);
  EXPECT_NEAR(tait_density(f, tait_pressure(f, 1010.0)), 1010.0, 1e-9);
  EXPECT_EQ(tait_density(f, 0.0), 1000.0);
}

TEST(SharedHash, IsSplitMix64) {
  // The published SplitMix64 stream from state 0: its first two outputs.
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  // The agitation draws its three velocities from that stream, seeded by run, frame and id.
  FluidParams f;
  f.kick_horizontal = 2.0;
  f.kick_up = 3.0;
  double v[3];
  agitation_velocity(f, 7, 4, 9, v);
  SplitMix64 same(splitmix64_mix(7 ^ splitmix64_mix(4 ^ (std::uint64_t{9} << 32))));
  EXPECT_EQ(v[0], -2.0 + 4.0 * static_cast<double>(same.next() >> 11) * 0x1.0p-53);
  EXPECT_EQ(v[1], -2.0 + 4.0 * static_cast<double>(same.next() >> 11) * 0x1.0p-53);
  EXPECT_EQ(v[2], 3.0 * static_cast<double>(same.next() >> 11) * 0x1.0p-53);
  double w[3];
  agitation_velocity(f, 7, 4, 10, w);  // another particle: other kicks
  EXPECT_NE(v[0], w[0]);
}

TEST(SharedGridWalk, ClampsAndFindsExactlyTheNeighbours) {
  GridGeometry g;
  for (int k = 0; k < 3; ++k) g.lo[k] = 0.0, g.inv_cell[k] = 4.0, g.n[k] = 4;  // cells 0.25 wide
  EXPECT_EQ(cell_coordinate(g, 0.3, 0), 1);
  EXPECT_EQ(cell_coordinate(g, -5.0, 0), 0);
  EXPECT_EQ(cell_coordinate(g, 7.0, 1), 3);
  EXPECT_EQ(cell_coordinate(g, std::nan(""), 2), 0);
  EXPECT_EQ(cell_key(g, 0.3, 0.6, 0.9), 1u + 4u * (2u + 4u * 3u));
  // 500 random points filed by cell; every query equals the brute force.
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x(500), y(500), z(500);
  std::vector<std::vector<std::uint32_t>> cells(64);
  for (std::uint32_t q = 0; q < 500; ++q) {
    x[q] = u(rng), y[q] = u(rng), z[q] = u(rng);
    cells[cell_key(g, x[q], y[q], z[q])].push_back(q);
  }
  const double support2 = 0.25 * 0.25;
  for (std::uint32_t i = 0; i < 500; i += 7) {
    std::vector<std::uint32_t> found;
    for_each_within(
        g, support2, x[i], y[i], z[i], x.data(), y.data(), z.data(),
        [&](std::uint64_t first, std::uint64_t last, auto&& visit) {
          for (std::uint64_t c = first; c <= last; ++c)
            for (std::uint32_t q : cells[c]) visit(q);
        },
        [&](std::uint32_t q, double, double, double, double) { found.push_back(q); });
    std::vector<std::uint32_t> brute;
    for (std::uint32_t q = 0; q < 500; ++q) {
      const double dx = x[i] - x[q], dy = y[i] - y[q], dz = z[i] - z[q];
      if (dx * dx + dy * dy + dz * dz < support2) brute.push_back(q);
    }
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, brute) << "particle " << i;
  }
}

// Particles and a brute-force neighbour visitor for running phases by hand.
struct Cloud {
  Particles p;
  double support = 0.0;
  StepView view(double dt = 0.0) {
    StepView s;
    s.a = p.view();
    s.dt = dt;
    s.domain = {{-10, -10, -10}, {10, 10, 10}};
    return s;
  }
  template <class Phase>
  void run(const Phase& phase, StepView s) {
    for (std::size_t i = 0; i < p.size(); ++i)
      phase(s, i, [&](auto&& fn) {
        for (std::uint32_t j = 0; j < p.size(); ++j) {
          if (j == i) continue;
          const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], dz = p.z[i] - p.z[j];
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 < support * support) fn(j, dx, dy, dz, r2);
        }
      });
  }
};

FluidParams seed_params() {
  FluidParams f;
  f.preset = Preset::seed;
  f.support = 0.5;
  f.particle_mass = 2.0;
  f.rest_density = 1.0;
  f.gas_constant = 3.0;
  f.viscosity = 0.25;
  f.gravity = {0.0, 0.0, -9.81};
  return f;
}

TEST(SharedPhases, SeedDensityAndAccelerationOfTwoParticles) {
  const FluidParams f = seed_params();
  Cloud c{{}, f.support};
  c.p.add({0, 0, 0}, {1, 0, 0}, 1.0, false);
  c.p.add({0.3, 0, 0}, {0, 0, 0}, 1.0, false);
  c.run(SeedDensity(f), c.view());
  // rho = m (W(0) + W(0.09)), poly6 with h = 0.5: norm (0.25^3 + 0.16^3).
  const double n6 = 315.0 / (64.0 * kPiHand * std::pow(0.5, 9));
  const double rho = 2.0 * n6 * (0.015625 + 0.004096);
  EXPECT_NEAR(c.p.rho[0], rho, 1e-12 * rho);
  EXPECT_EQ(c.p.rho[0], c.p.rho[1]);
  EXPECT_NEAR(c.p.p[0], 3.0 * (rho - 1.0), 1e-9 * rho);
  EXPECT_EQ(c.p.neighbours[0], 1u);
  c.run(SeedAcceleration(f), c.view());
  // On particle 0 (r_01 = (-0.3, 0, 0)): pressure -m p / rho * dwdr / r * dx, viscosity
  // mu m / rho lap W (v_1 - v_0); both over rho_0; gravity added.
  const double p = c.p.p[0];
  const double dwdr = -3.0 * 15.0 / (kPiHand * std::pow(0.5, 6)) * 0.04;
  const double pressure = -2.0 * p / rho * dwdr / 0.3 * -0.3 / rho;
  const double viscous = 0.25 * 2.0 / rho * 45.0 / (kPiHand * std::pow(0.5, 6)) * 0.2 * -1.0 / rho;
  EXPECT_NEAR(c.p.ax[0], pressure + viscous, 1e-9 * std::abs(pressure));
  EXPECT_NEAR(c.p.az[0], -9.81, 1e-12);
  // Momentum: the pair forces are equal and opposite.
  EXPECT_NEAR(c.p.ax[0] + c.p.ax[1], 0.0, 1e-12 * std::abs(pressure));
}

// The momentum the pair forces put in, summed over every particle of a random cloud with
// random velocities and densities (so every term is active): zero to round-off against the
// forces' own size, for both presets' acceleration phases.
TEST(SharedPhases, PairForcesSumToZeroMomentum) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Preset preset : {Preset::seed, Preset::water}) {
    FluidParams f = seed_params();
    f.gravity = {0, 0, 0};
    if (preset == Preset::water) {
      f.preset = Preset::water;
      f.smoothing_length = 0.13;
      f.support = 0.26;
      f.particle_mass = 1.0;
      f.rest_density = 1000.0;
      f.sound_speed = 20.0;
      f.alpha = 0.1;
    }
    Cloud c{{}, f.support};
    for (int i = 0; i < 300; ++i)
      c.p.add({0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng)}, {u(rng), u(rng), u(rng)},
              f.rest_density * (1.0 + 0.02 * u(rng)), false);
    if (preset == Preset::seed) {
      c.run(SeedDensity(f), c.view());
      c.run(SeedAcceleration(f), c.view());
    } else {
      for (std::size_t i = 0; i < c.p.size(); ++i) c.p.p[i] = tait_pressure(f, c.p.rho[i]);
      c.run(WaterAcceleration(f), c.view());
    }
    double sum[3] = {0, 0, 0}, size = 0.0;
    for (std::size_t i = 0; i < c.p.size(); ++i) {
      // m a_i: the seed's pair coefficient m^2 (p_i + p_j) / (2 rho_i rho_j) and the water's
      // m^2 (p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij) are symmetric, the gradients antisymmetric.
      const double m = f.particle_mass;
      const double a[3] = {c.p.ax[i], c.p.ay[i], c.p.az[i]};
      for (int k = 0; k < 3; ++k) sum[k] += m * a[k], size += std::abs(m * a[k]);
    }
    ASSERT_GT(size, 1.0) << to_string(preset);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(std::abs(sum[k]), 1e-10 * size) << to_string(preset) << " axis " << k;
  }
}

FluidParams water_params() {
  FluidParams f;
  f.preset = Preset::water;
  f.smoothing_length = 0.1;
  f.support = 0.2;
  f.particle_mass = 1.0;
  f.rest_density = 1000.0;
  f.sound_speed = 10.0;
  f.alpha = 0.1;
  f.gravity = {0, 0, -10.0};
  return f;
}

TEST(SharedPhases, WaterContinuityWallPressureAndIntegrate) {
  const FluidParams f = water_params();
  Cloud c{{}, f.support};
  c.p.add({0, 0, 0.1}, {0, 0, -1.0}, 1000.0, false);  // fluid, falling onto
  c.p.add({0, 0, 0.0}, {0, 0, 0}, 1000.0, true);      // a wall particle 0.1 below
  const double dt = 1e-3;
  c.run(WaterContinuity(f), c.view(dt));
  c.run(WaterDensityStep(f), c.view(dt));
  // drho = m (v_0 - 0) . (x_0 - x_1) dW/dr / r = 1 * (-1 * 0.1) * dwdr(0.1) / 0.1 > 0.
  const double nw = 21.0 / (16.0 * kPiHand * 1e-3);
  const double dwdr = -5.0 * nw / 0.1 * 0.125;
  EXPECT_NEAR(c.p.drho[0], -dwdr, 1e-9 * std::abs(dwdr));
  EXPECT_NEAR(c.p.rho[0], 1000.0 - dt * dwdr, 1e-9);
  EXPECT_NEAR(c.p.p[0], tait_pressure(f, c.p.rho[0]), 1e-9);
  EXPECT_EQ(c.p.drho[1], 0.0);  // walls are not integrated
  c.run(WallPressure(f), c.view(dt));
  // One fluid neighbour: p_w = p_0 + rho_0 g . (x_w - x_0) = p_0 + rho_0 * (-10) * (-0.1).
  EXPECT_NEAR(c.p.p[1], c.p.p[0] + c.p.rho[0] * 1.0, 1e-9);
  EXPECT_NEAR(c.p.rho[1], tait_density(f, c.p.p[1]), 1e-9);
  EXPECT_EQ(c.p.neighbours[1], 1u);
  // Symplectic Euler: v += dt a, then x += dt v (the new v).
  c.p.ax[0] = 1.0, c.p.ay[0] = 0.0, c.p.az[0] = 2.0;
  const Integrate integrate(f);
  integrate(c.view(dt), 0);
  EXPECT_DOUBLE_EQ(c.p.vx[0], dt * 1.0);
  EXPECT_DOUBLE_EQ(c.p.vz[0], -1.0 + dt * 2.0);
  EXPECT_DOUBLE_EQ(c.p.x[0], dt * dt * 1.0);
  EXPECT_DOUBLE_EQ(c.p.z[0], 0.1 + dt * (-1.0 + dt * 2.0));
  integrate(c.view(dt), 1);
  EXPECT_EQ(c.p.z[1], 0.0);  // a wall never moves
}

// delta-SPH: a denser neighbour at the same height raises the density rate by
// delta h c0 * 2 (rho_j - rho_i) (-dwdr / r) m / rho_j; two particles stacked at exactly the
// hydrostatic density difference rho0 g dz / c0^2 diffuse nothing.
TEST(SharedPhases, DensityDiffusionSpreadsOnlyTheNonHydrostaticPart) {
  FluidParams f = water_params();
  f.delta = 0.1;
  Cloud c{{}, f.support};
  c.p.add({0, 0, 0.5}, {}, 1000.0, false);
  c.p.add({0.1, 0, 0.5}, {}, 1010.0, false);  // same height, denser
  c.run(WaterContinuity(f), c.view(1e-3));
  const double nw = 21.0 / (16.0 * kPiHand * 1e-3);
  const double g = -5.0 * nw / 0.1 * 0.125 / 0.1;  // dwdr(0.1) / 0.1
  EXPECT_NEAR(c.p.drho[0], 0.1 * 0.1 * 10.0 * 2.0 * 10.0 * -g * 1.0 / 1010.0, 1e-9);
  EXPECT_NEAR(c.p.drho[1], -0.1 * 0.1 * 10.0 * 2.0 * 10.0 * -g * 1.0 / 1000.0, 1e-9);
  Cloud h{{}, f.support};
  const double lower = 1000.0 + 1000.0 * 10.0 * 0.1 / 100.0;  // rho0 g dz / c0^2 = 10 kg/m^3
  h.p.add({0, 0, 0.6}, {}, 1000.0, false);
  h.p.add({0, 0, 0.5}, {}, lower, false);
  h.run(WaterContinuity(f), h.view(1e-3));
  EXPECT_NEAR(h.p.drho[0], 0.0, 1e-9);
  EXPECT_NEAR(h.p.drho[1], 0.0, 1e-9);
}

// No-slip: a wall particle carries the mirror of the fluid's velocity (one fluid neighbour:
// exactly minus its velocity), a free-slip wall none; a fluid particle sliding past a no-slip
// wall is slowed, past a free-slip wall it is not.
TEST(SharedPhases, NoSlipWallsMirrorTheFluidAndSlowIt) {
  FluidParams f = water_params();
  f.no_slip = true;
  f.kinematic_viscosity = 1e-6;
  double ax[2];
  for (const std::uint8_t kind : {kNoSlipWall, kFreeSlipWall}) {
    Cloud c{{}, f.support};
    c.p.add({0, 0, 0.1}, {1.0, 0.0, 0.0}, 1000.0, false);
    c.p.add({0.05, 0, 0.0}, {}, 1000.0, true);
    c.p.wall[1] = kind;
    c.p.p[0] = 0.0;
    c.run(WallPressure(f), c.view());
    EXPECT_EQ(c.p.vx[1], kind == kNoSlipWall ? -1.0 : 0.0);
    c.p.p[1] = 0.0;  // no pressure: only the viscous terms act
    c.run(WaterAcceleration(f), c.view());
    ax[kind == kNoSlipWall ? 0 : 1] = c.p.ax[0];
  }
  EXPECT_LT(ax[0], -1e-3);  // slowed
  EXPECT_EQ(ax[1], 0.0);    // free slip: nothing viscous against the wall
}

TEST(SharedPushOut, LeavesThroughAClearFaceOfOverlappingBoxes) {
  // Box A [0,1]^3 and box B = A shifted by 0.9 in x; a particle 0.05 inside A's right face
  // would land in B's interior there, so it leaves A through its next nearest face (y = 1,
  // 0.1 away) instead.
  const Box3 domain{{-5, -5, -5}, {5, 5, 5}};
  const MovingBox boxes[2] = {{{{0, 0, 0}, {1, 1, 1}}, {}}, {{{0.9, 0, 0}, {1.9, 1, 1}}, {}}};
  double x[3] = {0.95, 0.9, 0.5}, v[3] = {0.0, 1.0, 0.0};
  push_out_of_obstacles(domain, boxes, 1, 0.5, x, v);  // A alone: out through x = 1
  EXPECT_EQ(x[0], 1.0);
  double y[3] = {0.95, 0.9, 0.5}, w[3] = {0.0, 1.0, 0.0};
  push_out_of_obstacles(domain, boxes, 2, 0.5, y, w);
  EXPECT_EQ(y[1], 1.0);
  EXPECT_EQ(y[0], 0.95);
  EXPECT_EQ(w[1], 1.0);  // already moving out: kept
}

// The frame check, fed each kind of bad particle: it must name the first one (by index) and
// say what is wrong, for the CPU's first_problem and the shared particle_problem alike.
TEST(SharedFrameCheck, NamesNaNsEscapesAndParticlesInABox) {
  FluidState s;
  s.domain = {{0, 0, 0}, {1, 1, 1}};
  s.boxes.push_back({{{0.4, 0.4, 0.4}, {0.6, 0.6, 0.6}}, {}});
  for (int i = 0; i < 6; ++i) s.particles.add({0.1 + 0.1 * i, 0.2, 0.2}, {}, 1000.0, false);
  s.fluid_count = 6;
  EXPECT_EQ(first_problem(s), "");
  s.particles.z[4] = 0.5, s.particles.y[4] = 0.5;  // x 0.5: inside the box
  EXPECT_EQ(first_problem(s), "particle 4 is inside an obstacle box");
  s.particles.x[3] = 1.2;
  EXPECT_EQ(first_problem(s), "particle 3 left the domain");
  s.particles.vy[2] = std::nan("");
  EXPECT_EQ(first_problem(s), "non-finite velocity of particle 2");
  s.particles.p[1] = INFINITY;
  EXPECT_EQ(first_problem(s), "non-finite density or pressure of particle 1");
  s.particles.y[0] = std::nan("");
  EXPECT_EQ(first_problem(s), "non-finite position of particle 0");
  // Wall particles are not checked (they sit outside the domain by design).
  s.particles.wall[0] = s.particles.wall[1] = s.particles.wall[2] = s.particles.wall[3] = 1;
  EXPECT_EQ(first_problem(s), "particle 4 is inside an obstacle box");
}

}  // namespace
}  // namespace hpcplan::sph
