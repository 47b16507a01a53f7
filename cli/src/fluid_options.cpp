#include "hpcplan/cli/fluid_options.hpp"

#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"

namespace hpcplan::cli {

void add_fluid_options(CLI::App* cmd, FluidArgs& a) {
  cmd->add_option("--preset", a.preset, "seed (the paper's parameters) | water (validated WCSPH)")
      ->capture_default_str();
  cmd->add_option("--scenario", a.scenario,
                  "seed: particles|static|dynamic (default particles); water: "
                  "dambreak|tank|column|marin (default dambreak)");
  add_number(cmd, "--particles", a.particles, "Fluid particles (water rounds to its lattice)", 1,
             200'000'000)
      ->capture_default_str();
  add_number(cmd, "--seed", a.seed, "Seed of the initial state and the boxes")
      ->capture_default_str();
  add_number(cmd, "--threads", a.threads, "OpenMP threads (default: OMP_NUM_THREADS or all)", 1,
             4096);
  cmd->add_option("--backend", a.backend,
                  "cpu (OpenMP) | cuda (the GPU; refused with the reason where it cannot run)")
      ->capture_default_str();
  add_number(cmd, "--memory-mb", a.memory_mb,
             "Refuse runs needing more memory (default: half the available)", 1, 1e9);
  for (const char* name : {"--preset", "--scenario", "--particles", "--seed"})
    a.problem_options.push_back(cmd->get_option(name));
}

sph::FluidOptions fluid_problem(const FluidArgs& a) {
  sph::FluidOptions o;
  o.preset = sph::parse_preset(a.preset);
  o.scenario = sph::parse_scenario(
      !a.scenario.empty() ? a.scenario
                          : (o.preset == sph::Preset::seed ? "particles" : "dambreak"));
  o.particles = a.particles;
  o.seed = a.seed;
  return o;
}

void require_memory(std::uint64_t need, std::size_t particles, double memory_mb,
                    const std::string& what) {
  const double budget =
      memory_mb > 0.0 ? memory_mb * 1048576.0 : 0.5 * static_cast<double>(available_memory_bytes());
  if (budget > 0.0 && static_cast<double>(need) > budget)
    throw InputError("--particles " + std::to_string(particles) + " needs about " +
                     std::to_string(need / 1048576) + " MiB" + what + ", over the budget of " +
                     std::to_string(static_cast<std::uint64_t>(budget / 1048576)) +
                     " MiB (--memory-mb)");
}

}  // namespace hpcplan::cli
