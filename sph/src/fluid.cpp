#include "hpcplan/sph/fluid.hpp"

#include <cmath>
#include <string>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/stopwatch.hpp"

namespace hpcplan::sph {

Fluid::Fluid(FluidState initial, std::unique_ptr<StepBackend> backend)
    : state_(std::move(initial)), backend_(std::move(backend)) {}

Fluid::Fluid(FluidState initial, std::string_view backend)
    : state_(std::move(initial)), backend_(make_backend(backend, state_)) {}

// The agitation of frame `frame`: a fresh velocity for every fluid particle, from a generator
// seeded by (run seed, frame, particle id).
void StepBackend::agitate(FluidState& s, std::uint64_t frame) {
  Particles& p = s.particles;
  const FluidParams& f = s.params;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (p.wall[i]) continue;
    SplitMix64 rng(splitmix64_mix(s.seed ^ splitmix64_mix(frame ^ (std::uint64_t{p.id[i]} << 32))));
    auto uniform = [&](double lo, double hi) {
      return lo + (hi - lo) * static_cast<double>(rng.next() >> 11) * 0x1.0p-53;
    };
    p.vx[i] = uniform(-f.kick_horizontal, f.kick_horizontal);
    p.vy[i] = uniform(-f.kick_horizontal, f.kick_horizontal);
    p.vz[i] = uniform(0.0, f.kick_up);
  }
}

std::string StepBackend::end_frame(FluidState& s) {
  return first_problem(s);
}

FrameReport Fluid::advance_frame(const std::function<void(const FluidState&)>& after_substep) {
  FrameReport report;
  Stopwatch clock;
  if (state_.params.agitate_every > 0 && frame_ > 0 &&
      frame_ % static_cast<std::uint64_t>(state_.params.agitate_every) == 0)
    backend_->agitate(state_, frame_);
  ++frame_;
  // The frame ends at an exact multiple of frame_dt, so that rounding never adds a sliver.
  const double end = static_cast<double>(frame_) * state_.params.frame_dt;
  while (state_.time < end) {
    double dt = backend_->stable_dt(state_);
    const double left = end - state_.time;
    // Split the rest of the frame evenly rather than leave a tiny last substep.
    const double pieces = std::ceil(left / dt - 1e-9);
    dt = pieces <= 1.0 ? left : left / pieces;
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      report.problem = "the stable substep is not a positive number";
      break;
    }
    report.grid_ms += backend_->substep(state_, dt).grid_ms;
    if (pieces <= 1.0) state_.time = end;
    ++report.substeps;
    if (after_substep) {
      backend_->sync_positions(state_);
      after_substep(state_);
    }
  }
  const std::string problem = backend_->end_frame(state_);
  report.ms = clock.milliseconds();
  if (report.problem.empty()) report.problem = problem;
  return report;
}

const FluidState& Fluid::state() const {
  backend_->sync_positions(state_);
  return state_;
}

const FluidState& Fluid::full_state() const {
  backend_->download(state_);
  return state_;
}

namespace {

// What is wrong with fluid particle i, or empty.
std::string problem_of(const FluidState& s, std::size_t i) {
  const Particles& p = s.particles;
  const Vec3 x = p.position(i), v = p.velocity(i);
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(x[k])) return "non-finite position of particle " + std::to_string(p.id[i]);
    if (!std::isfinite(v[k])) return "non-finite velocity of particle " + std::to_string(p.id[i]);
  }
  if (!std::isfinite(p.rho[i]) || !std::isfinite(p.p[i]))
    return "non-finite density or pressure of particle " + std::to_string(p.id[i]);
  if (!s.domain.contains(x)) return "particle " + std::to_string(p.id[i]) + " left the domain";
  for (const MovingBox& b : s.boxes)
    if (b.box.interior_contains(x))
      return "particle " + std::to_string(p.id[i]) + " is inside an obstacle box";
  return "";
}

}  // namespace

std::string first_problem(const FluidState& s) {
  // The scan runs in parallel; the lowest bad index is reported, whatever the thread count.
  const Particles& p = s.particles;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  std::ptrdiff_t first = n;
#pragma omp parallel for schedule(static) reduction(min : first)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    if (!p.wall[i] && i < first && !problem_of(s, static_cast<std::size_t>(i)).empty()) first = i;
  return first < n ? problem_of(s, static_cast<std::size_t>(first)) : "";
}

}  // namespace hpcplan::sph
