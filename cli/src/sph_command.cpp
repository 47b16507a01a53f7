// `hpcplan sph`: runs the fluid on its own: frames timed, VTK for ParaView, the dam break's
// surge front, a JSON or readable report.
#include <omp.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "hpcplan/cli/fluid_options.hpp"
#include "hpcplan/cli/fluid_session.hpp"
#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/cli/output_paths.hpp"
#include "hpcplan/cli/run_control.hpp"
#include "hpcplan/cli/vtk_dir.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/io/sph_report.hpp"
#include "hpcplan/io/vtk_fluid.hpp"
#include "hpcplan/sph/checkpoint.hpp"
#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::cli {
namespace {

struct SphArgs {
  FluidArgs fluid;
  std::uint64_t frames = 100;
  std::string vtk_dir, front_csv, gauges_csv, output;
  std::uint64_t every = 10;
  bool json = false;
  std::string checkpoint, restart;
  std::uint64_t checkpoint_every = 100;
};

std::string problem_words(const sph::FluidOptions& o) {
  return "--preset " + std::string(sph::to_string(o.preset)) + " --scenario " +
         std::string(sph::to_string(o.scenario)) + " --particles " + std::to_string(o.particles) +
         " --seed " + std::to_string(o.seed);
}

int run(const SphArgs& a) {
  sph::FluidOptions o = fluid_problem(a.fluid);
  // (A restart checks its checkpoint's options instead: the command line's defaults, a seed
  // preset with --scenario tank, say, need not make a valid problem of their own.)
  if (a.restart.empty()) sph::validate(o);
  // A restart continues the checkpoint's problem; options that name another are refused.
  std::optional<sph::FluidCheckpoint> restart;
  if (!a.restart.empty()) {
    restart = sph::read_checkpoint(a.restart);
    const sph::FluidOptions& saved = restart->options;
    auto given = [&](int k) { return a.fluid.problem_options[k]->count() > 0; };
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
  sph::check_backend_name(a.fluid.backend);
  require_memory(sph::estimated_bytes(o), o.particles, a.fluid.memory_mb);
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
  if (a.fluid.threads > 0) omp_set_num_threads(a.fluid.threads);

  FluidSession session = restart ? FluidSession(std::move(*restart), a.fluid.backend)
                                 : FluidSession(o, a.fluid.backend);
  const sph::Fluid& fluid = session.fluid();
  io::SphRun info = session.describe(a.fluid.threads > 0 ? a.fluid.threads : omp_get_max_threads());

  std::unique_ptr<io::VtkSeries> vtk;
  if (!a.vtk_dir.empty()) {
    vtk = std::make_unique<io::VtkSeries>(a.vtk_dir);
    if (session.restarted())  // the frames written before
      vtk->resume(session.restarted_at_frame(), fluid.state().params.frame_dt);
    else
      vtk->write(0, fluid.full_state());
  }
  auto save_checkpoint = [&] {
    return !a.checkpoint.empty() && session.write_checkpoint(a.checkpoint);
  };
  // SLURM's warning signal (or SIGTERM, Ctrl-C) ends the run at the next frame's end, with its
  // checkpoint, so that a requeued job continues with --restart (core/interrupt.hpp).
  const RunControl control = signal_control();
  const Stopwatch clock;
  info.report = session.advance(
      a.frames - fluid.frames_done(),
      [&](std::uint64_t frame, const sph::FluidState&) {
        if (vtk && (frame % a.every == 0 || frame == a.frames))
          vtk->write(frame, fluid.full_state());
        if (frame % a.checkpoint_every == 0 || frame == a.frames) save_checkpoint();
      },
      [&] { return control.should_stop(); });
  if (info.report.interrupted) {
    info.interrupted_by = control.stopped_by();
    // (At a multiple of --checkpoint-every this frame's checkpoint is already written.)
    const std::uint64_t frame = fluid.frames_done();
    if (frame % a.checkpoint_every == 0 ? !a.checkpoint.empty() : save_checkpoint())
      info.checkpoint = a.checkpoint;
  }
  if (session.restarted() && session.restarted_at_frame() == a.frames) save_checkpoint();
  info.seconds = clock.seconds();
  info.summary = sph::summarise(fluid.full_state());

  for (const std::string* csv : {&a.front_csv, &a.gauges_csv})
    if (!csv->empty()) write_file_atomically(*csv, io::probes_csv(session.probes()));
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
  add_fluid_options(cmd, a.fluid);
  add_number(cmd, "--frames", a.frames, "Frames of 0.02 s to simulate", 1, 100'000'000)
      ->capture_default_str();
  cmd->add_option("--vtk", a.vtk_dir, "Write VTK for ParaView into this directory (fluid.pvd)");
  add_number(cmd, "--every", a.every, "With --vtk: write every K-th frame", 1, 100'000'000)
      ->capture_default_str();
  cmd->add_option("--front-csv", a.front_csv, "Dam break: write the surge front as T,Z rows");
  cmd->add_option("--gauges-csv", a.gauges_csv,
                  "marin: write the water heights at SPHERIC Test 2's gauges as t,H1,H2,H3,H4 "
                  "rows (m, every 5 ms)");
  cmd->add_flag("--json", a.json, "Print the result as one JSON object");
  cmd->add_option("--checkpoint", a.checkpoint,
                  "Write the whole state to this file (atomically) every --checkpoint-every "
                  "frames and at the end");
  add_number(cmd, "--checkpoint-every", a.checkpoint_every, "With --checkpoint: every K frames", 1,
             100'000'000)
      ->capture_default_str();
  cmd->add_option("--restart", a.restart,
                  "Continue the run saved in this checkpoint, bit for bit, up to --frames");
  cmd->add_option("--output", a.output, "Also write the JSON result to this file (atomically)");
  refuse_empty_paths(cmd, {"--checkpoint", "--restart", "--front-csv", "--gauges-csv", "--output"});
  return [args](const Context& context) {
    if (context.comm && context.comm->size() > 1)
      throw InputError("hpcplan sph runs in one process (OpenMP threads); start it without mpirun");
    return run(*args);
  };
}

}  // namespace hpcplan::cli
