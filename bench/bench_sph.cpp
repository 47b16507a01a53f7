// The fluid's step and neighbour grid under Google Benchmark. One iteration is one substep of
// the stable length, on a fluid first run for a few substeps (so the particles have left their
// initial lattice or random order and the grid is in its steady reordered state).
//   Substep/<preset: 0 seed, 1 water>/<particles>/<threads>
//   GridBuild/<particles>/<threads>   the neighbour grid alone (the seed preset's box)
// Counters: particle_steps_per_s (fluid particles x substeps per second), particles, walls.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <memory>

#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/presets.hpp"

namespace {

using namespace hpcplan::sph;

void Substep(benchmark::State& state) {
  FluidOptions o;
  o.preset = state.range(0) == 0 ? Preset::seed : Preset::water;
  o.scenario = o.preset == Preset::seed ? Scenario::dynamic_boxes : Scenario::tank;
  o.particles = static_cast<std::size_t>(state.range(1));
  omp_set_num_threads(static_cast<int>(state.range(2)));
  FluidState s = make_fluid(o);
  auto backend = make_cpu_backend();
  for (int k = 0; k < 5; ++k) backend->substep(s, backend->stable_dt(s));
  for (auto _ : state) backend->substep(s, backend->stable_dt(s));
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(s.fluid_count), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["particles"] = static_cast<double>(s.fluid_count);
  state.counters["walls"] = static_cast<double>(s.particles.size() - s.fluid_count);
}

void GridBuild(benchmark::State& state) {
  FluidOptions o;
  o.particles = static_cast<std::size_t>(state.range(0));
  omp_set_num_threads(static_cast<int>(state.range(1)));
  FluidState s = make_fluid(o);
  auto backend = make_cpu_backend();
  for (int k = 0; k < 5; ++k) backend->substep(s, backend->stable_dt(s));
  for (auto _ : state) s.grid.build(s.particles);
  state.counters["particles_per_s"] = benchmark::Counter(
      static_cast<double>(s.particles.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["cells"] = static_cast<double>(s.grid.cells());
}

void Sizes(benchmark::internal::Benchmark* b) {
  for (int preset : {0, 1})
    for (long n : {1500L, 12500L, 25000L, 100000L, 1000000L})
      for (int threads : {1, 2}) b->Args({preset, n, threads});
}

BENCHMARK(Substep)->Apply(Sizes)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
BENCHMARK(GridBuild)
    ->ArgsProduct({{1500, 12500, 25000, 100000, 1000000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
