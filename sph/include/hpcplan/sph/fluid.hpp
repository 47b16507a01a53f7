#pragma once
// A fluid advancing frame by frame: CFL-limited substeps, none crossing a frame's end, run by
// a backend; after each frame, a check that every number is finite and every fluid particle is
// where the boundaries keep it.
//
// Threads: one thread drives a Fluid; the backend parallelises inside a substep. Readers on
// other threads copy what they need between frames (the simulator's snapshot); state() is
// called on the driving thread only (it may complete a copy from the GPU).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "hpcplan/sph/fluid_state.hpp"
#include "hpcplan/sph/physics/push_out.hpp"
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
  // `frames_done`: frames already run on `initial` (a restart from a checkpoint), so that the
  // next frame's number, end time and agitation are the uninterrupted run's.
  Fluid(FluidState initial, std::unique_ptr<StepBackend> backend, std::uint64_t frames_done = 0);
  // The backend by name ("cpu" or "cuda", see make_backend), made for this fluid.
  Fluid(FluidState initial, std::string_view backend, std::uint64_t frames_done = 0);

  // Advances by one frame (params.frame_dt). `after_substep`, if given, sees the state after
  // every substep (the dam break's surge front is read this way).
  FrameReport advance_frame(const std::function<void(const FluidState&)>& after_substep = {});

  // The state with its positions, ids and wall flags current (see step_backend.hpp); with the
  // CPU backend every array is current.
  const FluidState& state() const;
  // The state with every array current (a GPU backend copies them back: reports, VTK, tests).
  const FluidState& full_state() const;
  const StepBackend& backend() const { return *backend_; }
  std::uint64_t frames_done() const { return frame_; }

 private:
  // mutable: a backend that keeps the particles elsewhere completes its copies into it when a
  // reader asks (state() and full_state() are logically const).
  mutable FluidState state_;
  std::unique_ptr<StepBackend> backend_;
  std::uint64_t frame_ = 0;
};

// The first thing wrong with the state, or empty: a non-finite number, a fluid particle
// outside the domain or in an obstacle box's interior.
std::string first_problem(const FluidState& state);

// A particle's problem in words ("particle 7 left the domain"; "" for none), for every
// backend's frame check.
std::string describe(ParticleProblem kind, std::uint32_t id);

}  // namespace hpcplan::sph
