#include "hpcplan/sph/fluid.hpp"

#include <cmath>
#include <string>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/sph/physics.hpp"

namespace hpcplan::sph {

Fluid::Fluid(FluidState initial, std::unique_ptr<StepBackend> backend, std::uint64_t frames_done)
    : state_(std::move(initial)), backend_(std::move(backend)), frame_(frames_done) {}

Fluid::Fluid(FluidState initial, std::string_view backend, std::uint64_t frames_done)
    : state_(std::move(initial)), backend_(make_backend(backend, state_)), frame_(frames_done) {}

// The agitation of frame `frame`: a fresh velocity for every fluid particle, from a generator
// seeded by (run seed, frame, particle id).
void StepBackend::agitate(FluidState& s, std::uint64_t frame) {
  Particles& p = s.particles;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (p.wall[i]) continue;
    double v[3];
    agitation_velocity(s.params, s.seed, frame, p.id[i], v);
    p.vx[i] = v[0], p.vy[i] = v[1], p.vz[i] = v[2];
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

// What is wrong with fluid particle i (physics/push_out.hpp's check, which the CUDA backend
// runs too); words only for the one reported.
ParticleProblem problem_of(const FluidState& s, std::size_t i) {
  const Particles& p = s.particles;
  const double x[3] = {p.x[i], p.y[i], p.z[i]}, v[3] = {p.vx[i], p.vy[i], p.vz[i]};
  return particle_problem(s.domain, s.boxes.data(), static_cast<int>(s.boxes.size()), x, v,
                          p.rho[i], p.p[i]);
}

}  // namespace

std::string describe(ParticleProblem kind, std::uint32_t id) {
  if (kind == ParticleProblem::none) return "";
  const std::string who = "particle " + std::to_string(id);
  switch (kind) {
    case ParticleProblem::none:
      break;
    case ParticleProblem::position:
      return "non-finite position of " + who;
    case ParticleProblem::velocity:
      return "non-finite velocity of " + who;
    case ParticleProblem::density:
      return "non-finite density or pressure of " + who;
    case ParticleProblem::outside:
      return who + " left the domain";
    case ParticleProblem::in_box:
      return who + " is inside an obstacle box";
  }
  return who + " is unsound";
}

std::string first_problem(const FluidState& s) {
  // The scan runs in parallel; the lowest bad index is reported, whatever the thread count.
  const Particles& p = s.particles;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  std::ptrdiff_t first = n;
#pragma omp parallel for schedule(static) reduction(min : first)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    if (!p.wall[i] && i < first &&
        problem_of(s, static_cast<std::size_t>(i)) != ParticleProblem::none)
      first = i;
  return first < n ? describe(problem_of(s, static_cast<std::size_t>(first)), p.id[first]) : "";
}

}  // namespace hpcplan::sph
