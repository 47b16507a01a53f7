#pragma once
// The presets as solver types: each lists its force phases in order (phases.hpp); every
// substep is then grid -> the solver's phases -> Integrate. A backend writes only the loop that
// runs one phase over the particles (run(phase)) and picks the solver once with with_solver,
// so no backend branches on the preset.
#include "hpcplan/sph/physics/params.hpp"
#include "hpcplan/sph/physics/phases.hpp"

namespace hpcplan::sph {

struct SeedSolver {
  static constexpr Preset preset = Preset::seed;
  template <class Run>
  static void force_phases(const FluidParams& f, Run&& run) {
    run(SeedDensity(f));
    run(SeedAcceleration(f));
  }
};

struct WaterSolver {
  static constexpr Preset preset = Preset::water;
  template <class Run>
  static void force_phases(const FluidParams& f, Run&& run) {
    run(WaterContinuity(f));
    run(WaterDensityStep(f));
    run(WallPressure(f));
    run(WaterAcceleration(f));
  }
};

// fn(solver) with the solver type of `preset`.
template <class Fn>
decltype(auto) with_solver(Preset preset, Fn&& fn) {
  if (preset == Preset::seed) return fn(SeedSolver{});
  return fn(WaterSolver{});
}

}  // namespace hpcplan::sph
