// The CPU backend: the loops and bookkeeping around the one physics source (physics.hpp).
// Each phase runs as an OpenMP parallel for over the particles, reading each particle's
// neighbour list; a phase writes only its particle's entries, so there are no atomics and the
// result does not depend on the thread count. A substep: move the boxes; when the lists are
// stale (a frame's first substep, a particle moved half the skin, or every substep without a
// skin) build the grid, reorder the particles by cell when due and list the neighbours; run
// the preset's force phases (physics/solvers.hpp), then Integrate. With a skin the lists come
// from the backend's own wider grid and FluidState::grid is left as built (its geometry is
// what the CUDA backend reads).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

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

  // Lists are rebuilt at every frame's first substep: a run restarted from a checkpoint (taken
  // at a frame's end) lists its neighbours where the uninterrupted run did, so it continues
  // bit for bit.
  std::string end_frame(FluidState& s) override {
    lists_stale_ = true;
    return StepBackend::end_frame(s);
  }

  SubstepReport substep(FluidState& s, double dt) override {
    SubstepReport report;
    for (MovingBox& b : s.boxes) move_box(s.domain, b, dt);
    const Stopwatch clock;
    if (lists_stale_ || moved_beyond_half_skin(s)) {
      rebuild_lists(s);
      lists_stale_ = false;
    }
    report.grid_ms = clock.milliseconds();
    Particles& p = s.particles;
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
  // Grid (reordering the particles by cell when due) and lists for the fluid and for the walls
  // with fluid in reach (most of a tall tank's sides never see any and have nothing to
  // compute; without walls, as in the seed's scenarios, there is nothing to mark).
  void rebuild_lists(FluidState& s) {
    const FluidParams& f = s.params;
    Particles& p = s.particles;
    const double skin = f.list_skin > 0.0 ? f.list_skin * f.support : 0.0;
    if (skin > 0.0 && (!list_grid_ || list_grid_->support() != f.support + skin))
      list_grid_.emplace(s.grid.region(), f.support + skin);
    NeighbourGrid& grid = skin > 0.0 ? *list_grid_ : s.grid;
    grid.build(p);
    const bool reorder =
        f.reorder_every > 0 &&
        (skin > 0.0 || s.substeps % static_cast<std::uint64_t>(f.reorder_every) == 0);
    if (reorder) grid.sort_particles(p);
    const std::uint32_t capacity = list_capacity(f.preset);
    if (lists_.capacity() != capacity) lists_ = NeighbourLists(capacity);
    if (s.fluid_count < p.size()) grid.mark_cells_of(p, 0);
    // A wall particle's only pass (WallPressure) reads its fluid neighbours: its list keeps
    // those alone, about half of what it has within reach.
    lists_.build(
        grid, p, f.support,
        [&](std::size_t i) { return !p.wall[i] || grid.near_marked(p.x[i], p.y[i], p.z[i]); },
        [&](std::size_t i, std::uint32_t j) { return !p.wall[i] || !p.wall[j]; });
    list_grid_used_ = &grid;
    if (skin > 0.0) {
      x0_.assign(p.x.begin(), p.x.end());
      y0_.assign(p.y.begin(), p.y.end());
      z0_.assign(p.z.begin(), p.z.end());
      half_skin2_ = 0.25 * skin * skin;
    }
  }

  // Whether some fluid particle has moved more than half the skin since the lists were built
  // (two particles closing in by less than the skin keep their pair listed).
  bool moved_beyond_half_skin(const FluidState& s) const {
    if (!(s.params.list_skin > 0.0)) return true;  // lists every substep
    const Particles& p = s.particles;
    const Index n = static_cast<Index>(p.size());
    bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved)
    for (Index i = 0; i < n; ++i) {
      const double dx = p.x[i] - x0_[i], dy = p.y[i] - y0_[i], dz = p.z[i] - z0_[i];
      moved = moved || dx * dx + dy * dy + dz * dz > half_skin2_;
    }
    return moved;
  }

  // One force phase over every particle, its neighbours read from the lists. (A member
  // function, not a lambda nested in the solver's: clang rejects a capture of the substep's
  // locals from a generic lambda two levels down inside an OpenMP region.)
  template <class Phase>
  void run_phase(const Phase& phase, const StepView& view, const FluidState& s) const {
    const Particles& p = s.particles;
    const Index n = static_cast<Index>(p.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      phase(view, k, [&](auto&& fn) { lists_.for_each(k, *list_grid_used_, p, fn); });
    }
  }

  NeighbourLists lists_;
  std::optional<NeighbourGrid> list_grid_;  // cells one support plus the skin wide
  const NeighbourGrid* list_grid_used_ = nullptr;
  std::vector<double> x0_, y0_, z0_;  // positions when the lists were built
  double half_skin2_ = 0.0;
  bool lists_stale_ = true;  // rebuild at the next substep (a frame's first)
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
  // A packed water particle has ~75 neighbours within 2.6 dx and ~115 within the listed 2.6 dx
  // x 1.15 (the skin), the seed's gas a handful; more spill over to the grid (slower, still
  // exact).
  return preset == Preset::water ? 160 : 16;
}

std::unique_ptr<StepBackend> make_cpu_backend() {
  return std::make_unique<CpuBackend>();
}

}  // namespace hpcplan::sph
