#include "hpcplan/sph/run.hpp"

namespace hpcplan::sph {

RunReport run_frames(Fluid& fluid, std::uint64_t frames,
                     const std::function<void(std::uint64_t, const FluidState&)>& after_frame,
                     const std::function<void(const FluidState&)>& after_substep,
                     const std::function<bool()>& should_stop) {
  RunReport r;
  const std::uint64_t first = fluid.frames_done() + 1;
  r.frames = fluid.frames_done();
  for (std::uint64_t f = first; f < first + frames; ++f) {
    const FrameReport frame = fluid.advance_frame(after_substep);
    r.substeps += static_cast<std::uint64_t>(frame.substeps);
    r.frame_ms.push_back(frame.ms);
    r.grid_ms.push_back(frame.grid_ms);
    r.frames = f;
    if (after_frame) after_frame(f, fluid.state());
    if (!frame.problem.empty()) {
      r.stable = false;
      r.unstable_frame = f;
      r.problem = frame.problem;
      break;
    }
    if (should_stop && f + 1 < first + frames && should_stop()) {
      r.interrupted = true;
      break;
    }
  }
  return r;
}

}  // namespace hpcplan::sph
