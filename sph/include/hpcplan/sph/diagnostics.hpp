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
// Z = (x_front + dx / 2) / a, the front taken at the fluid's edge, half a spacing beyond the
// foremost particle (a = kDamBreakColumn, g from the state's gravity).
struct SurgeFront {
  double t = 0.0, z = 0.0;
};
SurgeFront dam_break_front(const FluidState& state);

}  // namespace hpcplan::sph
