#pragma once
// A fluid run as every front end drives it (hpcplan sph; the Python module's
// hpcplan.sph.Fluid): the fluid with what its run keeps beside it, the problem it was built
// from (what a checkpoint names), the scenario's probes read after every substep (the dam
// break's front, the MARIN gauges), and the frame a restart continued from. The executable and
// the module advance it alike, so their frames, probes and checkpoints are the same bytes.
//
// Threads: one thread drives a session at a time (sph::Fluid's rule).
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "hpcplan/io/sph_report.hpp"
#include "hpcplan/sph/checkpoint.hpp"
#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/run.hpp"

namespace hpcplan::cli {

class FluidSession {
 public:
  // A new fluid of a validated problem, on the backend by name ("cpu", "cuda").
  FluidSession(const sph::FluidOptions& options, std::string_view backend);
  // The run a checkpoint saved, continued bit for bit.
  FluidSession(sph::FluidCheckpoint checkpoint, std::string_view backend);

  const sph::FluidOptions& options() const { return options_; }
  sph::Fluid& fluid() { return fluid_; }
  const sph::Fluid& fluid() const { return fluid_; }
  const sph::Probes& probes() const { return probes_; }
  std::uint64_t frame() const { return fluid_.frames_done(); }
  // Whether it continues a checkpoint, and that checkpoint's frame (0 otherwise).
  bool restarted() const { return restarted_; }
  std::uint64_t restarted_at_frame() const { return restarted_at_; }

  // `frames` more frames (sph::run_frames: after_frame sees each frame's number, should_stop
  // ends the run at a frame's end), reading the probes after every substep.
  sph::RunReport advance(
      std::uint64_t frames,
      const std::function<void(std::uint64_t frame, const sph::FluidState&)>& after_frame = {},
      const std::function<bool()>& should_stop = {});

  // The state at the current frame's end as a checkpoint (sph/checkpoint.hpp), written
  // atomically, if it is sound; false, and nothing written, if it is not (the last checkpoint
  // stays the last sound one).
  bool write_checkpoint(const std::string& path) const;

  // A run's report with this session's problem, backend, domain and parameters filled in.
  io::SphRun describe(int threads) const;

 private:
  sph::FluidOptions options_;
  bool restarted_ = false;
  std::uint64_t restarted_at_ = 0;
  sph::Probes probes_;
  sph::Fluid fluid_;
};

}  // namespace hpcplan::cli
