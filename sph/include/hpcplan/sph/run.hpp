#pragma once
// A fluid run: F frames, timed one by one, stopped at the first frame that ends unsound (a
// non-finite number, a particle outside the domain or in an obstacle). The caller sees the
// state after every frame (to write VTK) and, optionally, after every substep.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hpcplan/sph/fluid.hpp"

namespace hpcplan::sph {

struct RunReport {
  bool stable = true;
  std::uint64_t unstable_frame = 0;  // the first unsound frame (1-based), when !stable
  std::string problem;
  bool interrupted = false;  // should_stop asked the run to end (at a frame's end)
  std::uint64_t frames = 0;  // frames completed (counted from the start of the run)
  std::uint64_t substeps = 0;
  std::vector<double> frame_ms, grid_ms;
};

// Runs `frames` more frames, numbered on from fluid.frames_done() (a restarted fluid carries
// on where its checkpoint stopped); after_frame sees each frame's number. should_stop, asked
// after each frame (after after_frame), ends the run there (interrupted).
RunReport run_frames(Fluid& fluid, std::uint64_t frames,
                     const std::function<void(std::uint64_t frame, const FluidState&)>& after_frame,
                     const std::function<void(const FluidState&)>& after_substep = {},
                     const std::function<bool()>& should_stop = {});

}  // namespace hpcplan::sph
