#pragma once
// The fluid's problem options that every front end shares (hpcplan sph, the Python module's
// hpcplan.sph.Fluid): --preset, --scenario, --particles, --seed, --threads, --backend and
// --memory-mb, read into sph::FluidOptions with their checks, and the memory budget check
// hpcplan sph and hpcplan sim both make before building a fluid.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "hpcplan/sph/presets.hpp"

namespace hpcplan::cli {

struct FluidArgs {
  std::string preset = "seed", scenario;
  std::size_t particles = 1500;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: OMP_NUM_THREADS or every core
  std::string backend = "cpu";
  double memory_mb = 0.0;  // 0: half of the available memory
  // --preset, --scenario, --particles, --seed: a restart refuses a value given here that
  // differs from its checkpoint's.
  std::vector<const CLI::Option*> problem_options;
};

void add_fluid_options(CLI::App* command, FluidArgs& args);

// The problem the options name (InputError for an unknown preset or scenario); the scenario
// defaults to the preset's (seed: particles, water: dambreak). Not validated: a restart checks
// its checkpoint's problem instead.
sph::FluidOptions fluid_problem(const FluidArgs& args);

// `need` bytes against --memory-mb (0: half of the available memory): InputError naming
// `particles` and `what` ("", " for the fluid") when over.
void require_memory(std::uint64_t need, std::size_t particles, double memory_mb,
                    const std::string& what = "");

}  // namespace hpcplan::cli
