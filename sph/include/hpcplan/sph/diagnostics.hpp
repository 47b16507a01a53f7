#pragma once
// What a run reports about the fluid (fluid particles only; walls are scaffolding). Every sum
// runs in index order on one thread, so a report is as deterministic as the state.
#include <cstdint>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

struct FluidSummary {
  std::size_t fluid = 0;
  double mass = 0.0;
  Vec3 momentum{};
  double kinetic_energy = 0.0;
  double max_density_error = 0.0;  // max |rho - rho0| / rho0
  double neighbours_mean = 0.0;
  std::uint32_t neighbours_max = 0;
  double max_speed = 0.0;
};

FluidSummary summarise(const FluidState& state);

// The dam break's surge front in Martin and Moyce's variables: T = t sqrt(2 g / a) and
// Z = x_front / a (a = kDamBreakColumn, g from the state's gravity). x_front is the farthest x
// on the sampling line near the floor (mid-width, half a spacing up: the first particle layer)
// where the fluid's kernel-interpolated density sum_j m W(x - x_j) reaches half the rest
// density, as DualSPHysics' validations measure it: a detached drop or a film thinner than the
// kernel does not count as the front. The floor and the two side walls of the slab count as
// mirrors (each fluid particle's reflections join the sum), so the water's interior reads rho0
// on the line, not the half or less that a truncated kernel would sum. Samples every dx / 8,
// the crossing interpolated between two samples. `density_fraction`: the threshold as a
// fraction of the rest density.
struct SurgeFront {
  double t = 0.0, z = 0.0;
};
SurgeFront dam_break_front(const FluidState& state, double density_fraction = 0.5);

}  // namespace hpcplan::sph
