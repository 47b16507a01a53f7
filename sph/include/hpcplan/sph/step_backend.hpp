#pragma once
// The one interface a physics backend implements: the stable substep for the current state,
// one substep of that length, and the frame boundaries at which readers see the particles.
// The CPU backend (OpenMP) works on the FluidState's own arrays; the CUDA backend keeps the
// particles on the GPU and brings back, between frames, only what readers need.
//
// What a FluidState holds while a backend runs it:
//   - always current on the host: time, substeps, boxes, parameters;
//   - after end_frame() (and sync_positions()): positions, ids and wall flags;
//   - after download(): every array (velocities, densities, pressures, accelerations, counts).
// The CPU backend keeps everything current at all times, so its frame calls are no-ops.
//
// Threads: a backend is used by the one thread that owns the Fluid; it may run its own
// parallel loops (or GPU streams) inside a call.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

struct SubstepReport {
  double grid_ms = 0.0;  // building the neighbour grid, reordering included
};

// What the stable substep depends on, reduced over the fluid particles.
struct StepLimits {
  double max_speed2 = 0.0;         // |v|^2
  double max_acceleration2 = 0.0;  // |a|^2 of the last substep
  std::uint32_t most_neighbours = 0;
  bool compressed = false;  // some particle denser than the rest density
};

// The largest substep the CFL, force and (seed preset) viscous limits allow; one formula for
// every backend.
double stable_dt_from(const FluidState& state, const StepLimits& limits);

class StepBackend {
 public:
  virtual ~StepBackend() = default;
  virtual std::string name() const = 0;
  // The largest substep the CFL, viscous and force limits allow now.
  virtual double stable_dt(const FluidState& state) = 0;
  // Neighbour grid, densities, pressures, accelerations, integration, boundaries.
  virtual SubstepReport substep(FluidState& state, double dt) = 0;

  // The seed preset's agitation of frame `frame` (see FluidParams::agitate_every).
  virtual void agitate(FluidState& state, std::uint64_t frame);
  // The frame is over: positions become current on the host (a backend may finish the copy
  // lazily, in sync_positions), and the first thing wrong with the fluid is returned (empty
  // when sound; see first_problem()).
  virtual std::string end_frame(FluidState& state);
  // Positions, ids and wall flags current on the host now.
  virtual void sync_positions(FluidState&) {}
  // Every array current on the host now.
  virtual void download(FluidState&) {}
};

// The CPU backend: every phase an OpenMP parallel for in which particle i writes only its own
// entries, so the result does not depend on the number of threads.
std::unique_ptr<StepBackend> make_cpu_backend();

// The CUDA backend for this state's particles (copied to the GPU once). InputError naming why
// when this build has no CUDA backend or no usable GPU is present.
std::unique_ptr<StepBackend> make_cuda_backend(const FluidState& state);

// Why `--backend cuda` cannot run here ("" when it can), and the GPU it would use.
std::string cuda_unavailable_reason();
std::string cuda_device_name();

// "cpu" or "cuda"; InputError for any other name, or for "cuda" when it cannot run here.
void check_backend_name(std::string_view name);
std::unique_ptr<StepBackend> make_backend(std::string_view name, const FluidState& state);

// The CPU backend's neighbour-list room per particle, for memory estimates.
std::uint32_t list_capacity(Preset preset);

}  // namespace hpcplan::sph
