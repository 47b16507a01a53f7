#pragma once
// The one interface a physics backend implements: the stable substep for the current state,
// and one substep of that length. The CPU backend (OpenMP) is here; a CUDA backend implements
// the same two calls on the same particle layout and parameters.
//
// Threads: a backend is used by the one thread that owns the Fluid; it may run its own
// parallel loops inside a call.
#include <memory>
#include <string>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

struct SubstepReport {
  double grid_ms = 0.0;  // building the neighbour grid, reordering included
};

class StepBackend {
 public:
  virtual ~StepBackend() = default;
  virtual std::string name() const = 0;
  // The largest substep the CFL, viscous and force limits allow now.
  virtual double stable_dt(const FluidState& state) const = 0;
  // Neighbour grid, densities, pressures, accelerations, integration, boundaries.
  virtual SubstepReport substep(FluidState& state, double dt) = 0;
};

// The CPU backend: every phase an OpenMP parallel for in which particle i writes only its own
// entries, so the result does not depend on the number of threads.
std::unique_ptr<StepBackend> make_cpu_backend();

// The CPU backend's neighbour-list room per particle, for memory estimates.
std::uint32_t list_capacity(Preset preset);

}  // namespace hpcplan::sph
