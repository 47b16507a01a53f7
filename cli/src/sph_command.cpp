// `hpcplan sph`: runs the fluid on its own: frames timed, VTK for ParaView, the dam break's
// surge front, a JSON or readable report.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/interrupt.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/io/sph_report.hpp"
#include "hpcplan/io/vtk_fluid.hpp"
#include "hpcplan/sph/checkpoint.hpp"
#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/presets.hpp"
#include "hpcplan/sph/run.hpp"
#include "number_options.hpp"
#include "output_paths.hpp"
#include "vtk_dir.hpp"

namespace hpcplan::cli {
namespace {

struct SphArgs {
  std::string preset = "seed", scenario;
  std::size_t particles = 1500;
  std::uint64_t frames = 100;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string vtk_dir, front_csv, gauges_csv, output, backend = "cpu";
  std::uint64_t every = 10;
  double memory_mb = 0.0;
  bool json = false;
  std::string checkpoint, restart;
  std::uint64_t checkpoint_every = 100;
  // --preset, --scenario, --particles, --seed: a restart refuses a value given here that
  // differs from its checkpoint's.
  std::vector<const CLI::Option*> problem_options;
};

std::string problem_words(const sph::FluidOptions& o) {
  return "--preset " + std::string(sph::to_string(o.preset)) + " --scenario " +
         std::string(sph::to_string(o.scenario)) + " --particles " + std::to_string(o.particles) +
         " --seed " + std::to_string(o.seed);
}

int run(const SphArgs& a) {
  sph::FluidOptions o;
  o.preset = sph::parse_preset(a.preset);
  o.scenario = sph::parse_scenario(
      !a.scenario.empty() ? a.scenario
                          : (o.preset == sph::Preset::seed ? "particles" : "dambreak"));
  o.particles = a.particles;
  o.seed = a.seed;
  // (A restart checks its checkpoint's options instead: the command line's defaults, a seed
  // preset with --scenario tank, say, need not make a valid problem of their own.)
  if (a.restart.empty()) sph::validate(o);
  // A restart continues the checkpoint's problem; options that name another are refused.
  std::optional<sph::FluidCheckpoint> restart;
  if (!a.restart.empty()) {
    restart = sph::read_checkpoint(a.restart);
    const sph::FluidOptions& saved = restart->options;
    auto given = [&](int k) { return a.problem_options[k]->count() > 0; };
    if ((given(0) && o.preset != saved.preset) || (given(1) && o.scenario != saved.scenario) ||
        (given(2) && o.particles != saved.particles) || (given(3) && o.seed != saved.seed))
      throw InputError("--restart '" + a.restart + "' continues " +
                       problem_words(restart->options) + ", not " + problem_words(o));
    o = restart->options;
    if (a.frames < restart->frame)
      throw InputError("--restart '" + a.restart + "' is at frame " +
                       std::to_string(restart->frame) + ", past --frames " +
                       std::to_string(a.frames));
  }
  if (!a.checkpoint.empty()) require_writable_destination(a.checkpoint, "--checkpoint");
  require_distinct_outputs({{&a.checkpoint, "--checkpoint"},
                            {&a.output, "--output"},
                            {&a.front_csv, "--front-csv"},
                            {&a.gauges_csv, "--gauges-csv"}});
  sph::check_backend_name(a.backend);
  // The memory budget: an explicit one, else half of what the machine has available.
  const std::uint64_t need = sph::estimated_bytes(o);
  const double budget = a.memory_mb > 0.0 ? a.memory_mb * 1048576.0
                                          : 0.5 * static_cast<double>(available_memory_bytes());
  if (budget > 0.0 && static_cast<double>(need) > budget)
    throw InputError("--particles " + std::to_string(o.particles) + " needs about " +
                     std::to_string(need / 1048576) + " MiB, over the budget of " +
                     std::to_string(static_cast<std::uint64_t>(budget / 1048576)) +
                     " MiB (--memory-mb)");
  if (!a.front_csv.empty()) {
    if (o.scenario != sph::Scenario::dambreak)
      throw InputError(
          "--front-csv records the dam break's surge front: it needs --scenario dambreak");
    require_writable_destination(a.front_csv, "--front-csv");
  }
  if (!a.gauges_csv.empty()) {
    if (o.scenario != sph::Scenario::marin)
      throw InputError(
          "--gauges-csv records SPHERIC Test 2's water heights: it needs --scenario marin");
    require_writable_destination(a.gauges_csv, "--gauges-csv");
  }
  if (!a.output.empty()) require_writable_destination(a.output, "--output");
  if (!a.vtk_dir.empty()) prepare_vtk_dir(a.vtk_dir);
  if (a.threads > 0) omp_set_num_threads(a.threads);

  sph::FluidState initial = restart ? std::move(restart->state) : sph::make_fluid(o);
  io::SphRun info;
  info.options = o;
  info.threads = a.threads > 0 ? a.threads : omp_get_max_threads();
  info.domain = initial.domain;
  info.params = initial.params;
  info.wall_particles = initial.particles.size() - initial.fluid_count;
  sph::Fluid fluid(std::move(initial), a.backend, restart ? restart->frame : 0);
  info.backend = fluid.backend().name();

  std::unique_ptr<io::VtkSeries> vtk;
  if (!a.vtk_dir.empty()) {
    vtk = std::make_unique<io::VtkSeries>(a.vtk_dir);
    if (restart)
      vtk->resume(restart->frame, fluid.state().params.frame_dt);  // the frames written before
    else
      vtk->write(0, fluid.full_state());
  }
  // The scenario's probes (the dam break's front, the MARIN gauges), read between substeps.
  sph::Probes probes = sph::probes_for(o.scenario);
  if (restart) probes.rows = std::move(restart->probe_rows);
  std::function<void(const sph::FluidState&)> watch;
  if (!probes.columns.empty()) {
    watch = [&probes](const sph::FluidState& s) { sph::record_probes(s, probes); };
    if (!restart) watch(fluid.state());
  }
  // The whole state at the end of `frame`, atomically, if it is sound (a frame that ended
  // unsound stops the run: the last checkpoint stays the last sound one).
  auto save_checkpoint = [&](std::uint64_t frame) {
    if (a.checkpoint.empty() || !sph::first_problem(fluid.full_state()).empty()) return false;
    write_file_atomically(a.checkpoint,
                          sph::encode_checkpoint(o, frame, fluid.full_state(), probes.rows));
    return true;
  };
  // SLURM's warning signal (or SIGTERM, Ctrl-C) ends the run at the next frame's end, with its
  // checkpoint, so that a requeued job continues with --restart (core/interrupt.hpp).
  interrupt::install();
  const Stopwatch clock;
  info.report = sph::run_frames(
      fluid, a.frames - fluid.frames_done(),
      [&](std::uint64_t frame, const sph::FluidState&) {
        if (vtk && (frame % a.every == 0 || frame == a.frames))
          vtk->write(frame, fluid.full_state());
        if (frame % a.checkpoint_every == 0 || frame == a.frames) save_checkpoint(frame);
      },
      watch, [] { return interrupt::requested() != 0; });
  if (info.report.interrupted) {
    info.interrupted_by = interrupt::name(interrupt::requested());
    // (At a multiple of --checkpoint-every this frame's checkpoint is already written.)
    const std::uint64_t frame = fluid.frames_done();
    if (frame % a.checkpoint_every == 0 ? !a.checkpoint.empty() : save_checkpoint(frame))
      info.checkpoint = a.checkpoint;
  }
  if (restart && restart->frame == a.frames) save_checkpoint(a.frames);
  if (restart) info.restarted_at_frame = restart->frame;
  info.seconds = clock.seconds();
  info.summary = sph::summarise(fluid.full_state());

  for (const std::string* csv : {&a.front_csv, &a.gauges_csv})
    if (!csv->empty()) write_file_atomically(*csv, io::probes_csv(probes));
  const std::string json = io::to_json(info).dump() + "\n";
  if (!a.output.empty()) write_file_atomically(a.output, json);
  std::fputs(a.json ? json.c_str() : io::to_summary(info).c_str(), stdout);
  return kExitOk;
}

}  // namespace

Action register_sph_command(CLI::App& app) {
  auto args = std::make_shared<SphArgs>();
  SphArgs& a = *args;
  CLI::App* cmd = app.add_subcommand("sph", "Run the SPH fluid (seed 000's dynamic obstacles)");
  cmd->add_option("--preset", a.preset, "seed (the paper's parameters) | water (validated WCSPH)")
      ->capture_default_str();
  cmd->add_option("--scenario", a.scenario,
                  "seed: particles|static|dynamic (default particles); water: "
                  "dambreak|tank|column|marin (default dambreak)");
  add_number(cmd, "--particles", a.particles, "Fluid particles (water rounds to its lattice)", 1,
             200'000'000)
      ->capture_default_str();
  add_number(cmd, "--frames", a.frames, "Frames of 0.02 s to simulate", 1, 100'000'000)
      ->capture_default_str();
  add_number(cmd, "--seed", a.seed, "Seed of the initial state and the boxes")
      ->capture_default_str();
  add_number(cmd, "--threads", a.threads, "OpenMP threads (default: OMP_NUM_THREADS or all)", 1,
             4096);
  cmd->add_option("--backend", a.backend,
                  "cpu (OpenMP) | cuda (the GPU; refused with the reason where it cannot run)")
      ->capture_default_str();
  cmd->add_option("--vtk", a.vtk_dir, "Write VTK for ParaView into this directory (fluid.pvd)");
  add_number(cmd, "--every", a.every, "With --vtk: write every K-th frame", 1, 100'000'000)
      ->capture_default_str();
  cmd->add_option("--front-csv", a.front_csv, "Dam break: write the surge front as T,Z rows");
  cmd->add_option("--gauges-csv", a.gauges_csv,
                  "marin: write the water heights at SPHERIC Test 2's gauges as t,H1,H2,H3,H4 "
                  "rows (m, every 5 ms)");
  add_number(cmd, "--memory-mb", a.memory_mb,
             "Refuse runs needing more memory (default: half the available)", 1, 1e9);
  cmd->add_flag("--json", a.json, "Print the result as one JSON object");
  cmd->add_option("--checkpoint", a.checkpoint,
                  "Write the whole state to this file (atomically) every --checkpoint-every "
                  "frames and at the end");
  add_number(cmd, "--checkpoint-every", a.checkpoint_every, "With --checkpoint: every K frames", 1,
             100'000'000)
      ->capture_default_str();
  cmd->add_option("--restart", a.restart,
                  "Continue the run saved in this checkpoint, bit for bit, up to --frames");
  for (const char* name : {"--preset", "--scenario", "--particles", "--seed"})
    a.problem_options.push_back(cmd->get_option(name));
  cmd->add_option("--output", a.output, "Also write the JSON result to this file (atomically)");
  refuse_empty_paths(cmd, {"--checkpoint", "--restart", "--front-csv", "--gauges-csv", "--output"});
  return [args](const Context& context) {
    if (context.comm && context.comm->size() > 1)
      throw InputError("hpcplan sph runs in one process (OpenMP threads); start it without mpirun");
    return run(*args);
  };
}

}  // namespace hpcplan::cli
