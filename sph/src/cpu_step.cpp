// The CPU backend: the loops and bookkeeping around the one physics source (physics.hpp).
// Each phase runs as an OpenMP parallel for over the particles, reading each particle's
// neighbour list; a phase writes only its particle's entries, so there are no atomics and the
// result does not depend on the thread count. A substep: move the boxes, build the grid
// (reorder the particles by cell every few substeps), list the neighbours, run the preset's
// force phases (physics/solvers.hpp), then Integrate.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/sph/boundaries.hpp"
#include "hpcplan/sph/neighbour_lists.hpp"
#include "hpcplan/sph/physics.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

namespace {

using Index = std::ptrdiff_t;

class CpuBackend final : public StepBackend {
 public:
  std::string name() const override { return "cpu"; }

  double stable_dt(const FluidState& s) override {
    const Particles& p = s.particles;
    const Index n = static_cast<Index>(p.size());
    double v2 = 0.0, a2 = 0.0;
    std::uint32_t most_neighbours = 0;
    bool compressed = false;
#pragma omp parallel for schedule(static) reduction(max                        \
                                                    : v2, a2, most_neighbours) \
    reduction(||                                                               \
              : compressed)
    for (Index i = 0; i < n; ++i) {
      if (p.wall[i]) continue;
      v2 = std::max(v2, p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      a2 = std::max(a2, p.ax[i] * p.ax[i] + p.ay[i] * p.ay[i] + p.az[i] * p.az[i]);
      most_neighbours = std::max(most_neighbours, p.neighbours[i]);
      compressed = compressed || p.rho[i] > s.params.rest_density;
    }
    return stable_dt_from(s, {v2, a2, most_neighbours, compressed});
  }

  SubstepReport substep(FluidState& s, double dt) override {
    SubstepReport report;
    for (MovingBox& b : s.boxes) move_box(s.domain, b, dt);
    const Stopwatch clock;
    s.grid.build(s.particles);
    if (s.params.reorder_every > 0 &&
        s.substeps % static_cast<std::uint64_t>(s.params.reorder_every) == 0)
      s.grid.sort_particles(s.particles);
    Particles& p = s.particles;
    const std::uint32_t capacity = list_capacity(s.params.preset);
    if (lists_.capacity() != capacity) lists_ = NeighbourLists(capacity);
    // Lists for the fluid, and for the walls with fluid in reach (most of a tall tank's sides
    // never see any and have nothing to compute). Without walls (the seed's scenarios) there
    // is nothing to mark.
    const bool has_walls = s.fluid_count < p.size();
    if (has_walls) s.grid.mark_cells_of(p, 0);
    lists_.build(s.grid, p, [&](std::size_t i) {
      return !p.wall[i] || s.grid.near_marked(p.x[i], p.y[i], p.z[i]);
    });
    report.grid_ms = clock.milliseconds();
    const StepView view{p.view(), dt, s.domain, s.boxes.data(), static_cast<int>(s.boxes.size())};
    const Index n = static_cast<Index>(p.size());
    with_solver(s.params.preset, [&](auto solver) {
      decltype(solver)::force_phases(s.params,
                                     [&](const auto& phase) { run_phase(phase, view, s); });
    });
    const Integrate integrate(s.params);
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i) integrate(view, static_cast<std::size_t>(i));
    s.time += dt;
    ++s.substeps;
    return report;
  }

 private:
  // One force phase over every particle, its neighbours read from the lists. (A member
  // function, not a lambda nested in the solver's: clang rejects a capture of the substep's
  // locals from a generic lambda two levels down inside an OpenMP region.)
  template <class Phase>
  void run_phase(const Phase& phase, const StepView& view, const FluidState& s) const {
    const Particles& p = s.particles;
    const NeighbourGrid& grid = s.grid;
    const Index n = static_cast<Index>(p.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      phase(view, k, [&](auto&& fn) { lists_.for_each(k, grid, p, fn); });
    }
  }

  NeighbourLists lists_;
};

}  // namespace

double stable_dt_from(const FluidState& s, const StepLimits& limits) {
  const FluidParams& f = s.params;
  double v2 = limits.max_speed2, a2 = limits.max_acceleration2;
  for (const MovingBox& b : s.boxes) v2 = std::max(v2, dot(b.velocity, b.velocity));
  // The signal speed: the flow plus sound. The seed's EOS clamps at the rest density, so
  // sound (sqrt(k)) only travels where some particle is compressed.
  double c = f.sound_speed;
  if (f.preset == Preset::seed) c = limits.compressed ? std::sqrt(f.gas_constant) : 0.0;
  const double h = f.preset == Preset::water ? f.smoothing_length : f.support;
  a2 = std::max(a2, dot(f.gravity, f.gravity));
  double dt = f.frame_dt;
  const double speed = c + std::sqrt(v2);
  if (speed > 0.0) dt = std::min(dt, f.cfl * h / speed);
  if (a2 > 0.0) dt = std::min(dt, f.cfl * std::sqrt(h / std::sqrt(a2)));
  if (f.preset == Preset::seed && f.viscosity > 0.0) {
    // Müller's viscous acceleration relaxes a velocity difference at a rate of at most
    // mu m lap W(0) / rho^2 per neighbour, rho no less than a particle's own density: keep
    // the explicit update well inside its stability limit.
    const double rho_min = f.particle_mass * Poly6Kernel(f.support).w(0.0);
    const double rate = f.viscosity * f.particle_mass * ViscosityKernel(f.support).laplacian(0.0) /
                        (rho_min * rho_min) * std::max<std::uint32_t>(1, limits.most_neighbours);
    dt = std::min(dt, 0.5 / rate);
  }
  return dt;
}

std::uint32_t list_capacity(Preset preset) {
  // A packed water particle has ~75 neighbours within 2.6 dx, the seed's gas a handful; more
  // spill over to the grid (slower, still exact).
  return preset == Preset::water ? 96 : 16;
}

std::unique_ptr<StepBackend> make_cpu_backend() {
  return std::make_unique<CpuBackend>();
}

}  // namespace hpcplan::sph
