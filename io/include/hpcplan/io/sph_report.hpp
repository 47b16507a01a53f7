#pragma once
// A fluid run (hpcplan sph) as JSON (the keys documented in README.md) and as a readable
// summary, and a scenario's probe rows (the dam break's front, the MARIN gauges) as CSV.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/presets.hpp"
#include "hpcplan/sph/run.hpp"

namespace hpcplan::io {

struct SphRun {
  sph::FluidOptions options;
  int threads = 1;
  std::string backend;
  sph::Box3 domain;
  std::size_t wall_particles = 0;
  sph::FluidParams params;
  sph::RunReport report;
  sph::FluidSummary summary;  // after the last frame
  double seconds = 0.0;       // the whole run, set-up excluded
  // A restarted run: the checkpoint's frame (0: from the start). The report's substeps and
  // frame times are this process's frames, after it.
  std::uint64_t restarted_at_frame = 0;
  // An interrupted run (report.interrupted): the signal that asked it to end ("SIGUSR1", ...)
  // and the checkpoint written at its last frame ("" without --checkpoint).
  std::string interrupted_by, checkpoint;
};

nlohmann::json to_json(const SphRun& run);
std::string to_summary(const SphRun& run);

// A scenario's probe rows as CSV (sph::Probes: the dam break's T,Z, the MARIN gauges' t and
// heights), six decimals.
std::string probes_csv(const sph::Probes& probes);

}  // namespace hpcplan::io
