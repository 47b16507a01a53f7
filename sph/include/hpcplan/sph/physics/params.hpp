#pragma once
// The parameters the fluid's phases read, and the obstacle boxes they push particles out of:
// plain data that the CPU loops read from the FluidState and that a CUDA kernel takes by
// value, so that both backends read one set of numbers (no device copy of the parameters).
//
// C++17 (nvcc compiles it for the CUDA backend); Vec3 and Box3 are std::arrays, which device
// code indexes through their constexpr operator[].
#include <cstdint>

#include "hpcplan/sph/vec3.hpp"

namespace hpcplan::sph {

enum class Preset {
  seed,   // seed 000: Müller kernels and the paper's parameters (a pressureless particle gas)
  water,  // weakly-compressible water: Wendland C2, Tait EOS, wall particles, validated
};

struct FluidParams {
  Preset preset = Preset::seed;
  double particle_mass = 0.05;
  double rest_density = 1000.0;
  double support = 0.15;           // kernel support radius (seed: H; water: 2h)
  double smoothing_length = 0.15;  // water: h (the seed's kernels use only the support)
  Vec3 gravity{0.0, 0.0, -9.81};
  // seed: p = gas_constant * max(0, rho - rest_density); viscosity mu of Müller's force.
  double gas_constant = 2000.0;
  double viscosity = 0.1;
  // water: Tait EOS p = B ((rho / rho0)^7 - 1), B = rho0 c0^2 / 7; Monaghan's viscosity alpha.
  double sound_speed = 0.0;
  double alpha = 0.02;
  // water: delta-SPH density diffusion (Molteni and Colagrossi 2009, with Fourtakas et al.
  // 2019's hydrostatic part removed), coefficient delta (0.1 in the literature; 0: off).
  double delta = 0.0;
  // water: no-slip walls (Adami et al. 2012): each wall particle carries the mirror of the
  // fluid's velocity around it, and fluid-wall pairs feel the viscous terms with it: Monaghan's
  // and water's own laminar viscosity (Morris et al. 1997), kinematic viscosity nu (m^2/s).
  bool no_slip = false;
  double kinematic_viscosity = 0.0;
  double particle_spacing = 0.0;  // water: dx, the initial lattice spacing
  double frame_dt = 0.02;         // seconds per frame; substeps never cross a frame's end
  double cfl = 0.25;              // dt <= cfl * h / (c + |v|max), and <= cfl sqrt(h / |a|max)
  double restitution = 0.5;       // normal velocity kept (reversed) at walls and box faces
  int reorder_every = 4;          // substeps between reorderings of the particles by cell
  // The CPU backend's neighbour lists (Verlet): listed within support x (1 + list_skin) and
  // kept while no particle has moved half the skin, rebuilt at every frame's start (so that a
  // restart from a frame boundary rebuilds where the uninterrupted run did). 0: listed afresh
  // every substep (the seed's fast gas would outrun any skin); then the particles are
  // reordered every reorder_every substeps, else at every rebuild. Performance only: the
  // neighbours within the support are the same, in another order of summation.
  double list_skin = 0.0;
  // seed: every this many frames (0: never), each fluid particle is given a fresh random
  // velocity, +-kick_horizontal on x and y and 0..kick_up on z, drawn from the run's seed, the
  // frame and the particle's id (so the thread count and the particle order do not matter).
  int agitate_every = 0;
  double kick_horizontal = 2.5, kick_up = 3.0;
};

// An obstacle box moving at a fixed velocity, reflected off the domain's walls (a static box
// has zero velocity).
struct MovingBox {
  Box3 box;
  Vec3 velocity{};
};

}  // namespace hpcplan::sph
