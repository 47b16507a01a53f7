#pragma once
// A fluid advancing frame by frame: CFL-limited substeps, none crossing a frame's end, run by
// a backend; after each frame, a check that every number is finite and every fluid particle is
// where the boundaries keep it.
//
// Threads: one thread drives a Fluid; the backend parallelises inside a substep. Readers on
// other threads copy what they need between frames (the simulator's snapshot).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "hpcplan/sph/fluid_state.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

struct FrameReport {
  int substeps = 0;
  double ms = 0.0;       // wall time of the frame
  double grid_ms = 0.0;  // of which building the neighbour grid (and reordering)
  // Empty when the frame ended sound; otherwise what went wrong ("non-finite velocity of
  // particle 12", "particle 7 left the domain").
  std::string problem;
};

class Fluid {
 public:
  Fluid(FluidState initial, std::unique_ptr<StepBackend> backend);

  // Advances by one frame (params.frame_dt). `after_substep`, if given, sees the state after
  // every substep (the dam break's surge front is read this way).
  FrameReport advance_frame(const std::function<void(const FluidState&)>& after_substep = {});

  const FluidState& state() const { return state_; }
  const StepBackend& backend() const { return *backend_; }

 private:
  FluidState state_;
  std::unique_ptr<StepBackend> backend_;
  std::uint64_t frame_ = 0;
};

// The first thing wrong with the state, or empty: a non-finite number, a fluid particle
// outside the domain or in an obstacle box's interior.
std::string first_problem(const FluidState& state);

}  // namespace hpcplan::sph
