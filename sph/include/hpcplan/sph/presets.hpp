#pragma once
// Ready-made fluids.
//
// seed (seed 000's parameters): a cube of side L = 5 (N / 1500)^(1/3), H = 0.15, mass 0.05,
//   rest density 1000, gas constant 2000, viscosity 0.1, Müller's kernels. With these numbers a
//   particle's own density is ~23 and packed neighbourhoods reach ~70-175, far below the rest
//   density, so the clamped EOS never produces pressure: the fluid is a viscous particle gas.
//   Its regime (a dense moving field filling the box) is reproduced as the published code
//   produces it, with the physics written correctly:
//     - particles start uniformly at random in the free part of the box (seeded), each with
//       the published agitation kick: +-2.5 m/s on each horizontal axis, 0..3 m/s up;
//     - the kick is repeated every 250 frames (5 s). The published code kicks once; with a
//       single kick the gas here loses 99% of its kinetic energy within 40 s (walls keep half
//       the normal speed), long before a replanning run ends, and packs on the floor. Kicked
//       again, the field stays the dense moving cloud the paper describes for as long as a
//       run lasts;
//     - gravity is the published code's effective acceleration, 0.02 m/s^2 down (it adds m g
//       as a force and divides by the density; here it is an acceleration, stated as such);
//     - walls and box faces keep half the normal velocity, reversed.
//   Scenarios: particles; static (6 boxes, sides 0.1-0.2 L, seeded, not overlapping);
//   dynamic (the same boxes at 0.5-1.0 wu/s in seeded directions, reflected off the walls).
// water (weakly-compressible SPH that passes validation): Wendland C2 with h = 1.3 dx, mass
//   rho0 dx^3, Tait EOS with c0 = 10 sqrt(2 g H) (H the fluid's height; ten times the largest
//   free-fall speed), Monaghan viscosity alpha = 0.1, free-slip walls of three layers of
//   particles carrying extrapolated pressures (Adami et al. 2012), hydrostatic initial density.
//   Scenarios: tank (water 0.5 m deep in a 1 m x 1 m tank), dambreak (Martin and Moyce's
//   column: width a = 2.25 in, height 2a, in a tank 6a long, a/4 wide) and column (a dam break
//   at a robot's scale for the simulator: a column 1 m x 1 m x 2 m standing in the middle of a
//   tank 4 m long, 1 m wide and 3 m tall, so it collapses both ways; the columns of particles
//   across the column's width are an even number, nx = 2, 4, ...), and marin (SPHERIC Test 2,
//   MARIN's dam break with an obstacle, Kleefsman et al. 2005: a tank 3.22 x 1 x 1 m, the water
//   column 1.228 m long and 0.55 m deep against its far end (x >= 1.992), a box 0.161 x 0.403 x
//   0.161 m standing on the floor at x = 0.6635-0.8245, centred across the tank. The column's
//   height is exact; the other planes are snapped to the nearest lattice plane (dx = 0.55 / nz,
//   so within dx / 2). The tank's top is a lid at 1 m: water rising along the end wall stops
//   there).
#include <cstdint>
#include <string_view>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

enum class Scenario { particles, static_boxes, dynamic_boxes, dambreak, tank, column, marin };

Preset parse_preset(std::string_view name);      // InputError if unknown
Scenario parse_scenario(std::string_view name);  // InputError if unknown
std::string_view to_string(Scenario s);

struct FluidOptions {
  Preset preset = Preset::seed;
  Scenario scenario = Scenario::particles;
  std::size_t particles = 1500;  // fluid particles asked for (water rounds to its lattice)
  std::uint64_t seed = 1;
};

// Checks the options (InputError: no particles, a scenario the preset does not support).
void validate(const FluidOptions& options);

// Bytes the fluid will hold (particles, walls, neighbour grid), without building it.
std::uint64_t estimated_bytes(const FluidOptions& options);

FluidState make_fluid(const FluidOptions& options);

// The dam break's column width a, for Z = x / a and T = t sqrt(2 g / a).
inline constexpr double kDamBreakColumn = 0.05715;

// SPHERIC Test 2's geometry (metres; x along the tank from the end the water runs to, y across,
// z up): the tank, the water column (against the tank's far end) and the obstacle.
inline constexpr Vec3 kMarinTank{3.22, 1.0, 1.0};
inline constexpr Vec3 kMarinColumn{1.228, 1.0, 0.55};
inline constexpr Box3 kMarinObstacle{{0.6635, 0.2985, 0.0}, {0.8245, 0.7015, 0.161}};

}  // namespace hpcplan::sph
