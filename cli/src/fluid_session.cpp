#include "hpcplan/cli/fluid_session.hpp"

#include <utility>

#include "hpcplan/core/atomic_file.hpp"

namespace hpcplan::cli {

FluidSession::FluidSession(const sph::FluidOptions& options, std::string_view backend)
    : options_(options),
      probes_(sph::probes_for(options.scenario)),
      fluid_(sph::make_fluid(options), backend) {
  if (!probes_.columns.empty()) sph::record_probes(fluid_.state(), probes_);  // at the start
}

FluidSession::FluidSession(sph::FluidCheckpoint checkpoint, std::string_view backend)
    : options_(checkpoint.options),
      restarted_(true),
      restarted_at_(checkpoint.frame),
      probes_(sph::probes_for(checkpoint.options.scenario)),
      fluid_(std::move(checkpoint.state), backend, checkpoint.frame) {
  probes_.rows = std::move(checkpoint.probe_rows);
}

sph::RunReport FluidSession::advance(
    std::uint64_t frames,
    const std::function<void(std::uint64_t, const sph::FluidState&)>& after_frame,
    const std::function<bool()>& should_stop) {
  std::function<void(const sph::FluidState&)> watch;
  if (!probes_.columns.empty())
    watch = [this](const sph::FluidState& s) { sph::record_probes(s, probes_); };
  return sph::run_frames(fluid_, frames, after_frame, watch, should_stop);
}

bool FluidSession::write_checkpoint(const std::string& path) const {
  const sph::FluidState& s = fluid_.full_state();
  if (!sph::first_problem(s).empty()) return false;
  write_file_atomically(path, sph::encode_checkpoint(options_, frame(), s, probes_.rows));
  return true;
}

io::SphRun FluidSession::describe(int threads) const {
  io::SphRun info;
  info.options = options_;
  info.threads = threads;
  info.backend = fluid_.backend().name();
  const sph::FluidState& s = fluid_.state();
  info.domain = s.domain;
  info.params = s.params;
  info.wall_particles = s.particles.size() - s.fluid_count;
  info.restarted_at_frame = restarted_at_;
  return info;
}

}  // namespace hpcplan::cli
