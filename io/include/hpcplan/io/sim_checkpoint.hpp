#pragma once
// The simulator's checkpoint (hpcplan sim --checkpoint / --restart): the runs finished so far.
//
// What is saved, and why it suffices: the runs are independent (each builds its fluid, robot,
// goal and planners from (seed, run number) and nothing else), so a restart keeps the finished
// runs' records (every RunRecord and ReplanRecord field, and their trajectory rows) and makes the
// remaining runs, a run cut short from its start. In lockstep pace the restarted invocation's
// CSVs and JSON then equal the uninterrupted one's (timings aside). A run is not saved within
// itself: the planners' state between replans (D* Lite's incremental search, the planner
// thread's plan in flight) is not serialisable as it stands, and a bitwise continuation needs it.
// Every option that decides a run's result is saved as text and must be the restart's own, but
// for --runs, which may grow, and --threads, on which no result depends (the fluid's sums are
// the same with any thread count); whether trajectory rows are recorded must match too, so
// that --trajectory covers every run.
//
// The file: core's checkpoint envelope around a CBOR document (binary IEEE doubles, so every
// figure, infinities included, comes back bit for bit).
#include <string>
#include <vector>

#include "hpcplan/io/sim_report.hpp"
#include "hpcplan/sim/simulator.hpp"

namespace hpcplan::io {

struct SimCheckpoint {
  std::string options;  // sim_checkpoint_options() of the invocation that wrote it
  sim::SimResult result;
  std::vector<TrajectoryRow> trajectory;
};

// The options that decide a simulation's results, as one line of JSON (--runs left out), and
// whether the invocation records trajectory rows.
std::string sim_checkpoint_options(const sim::SimOptions& options, bool trajectory);

std::string encode_sim_checkpoint(const SimCheckpoint& checkpoint);
// InputError "--restart 'NAME': ..." when damaged, foreign or of another version.
SimCheckpoint decode_sim_checkpoint(std::string_view bytes, const std::string& name);
// What decode_sim_checkpoint reads inside the envelope (the CBOR payload, after the envelope's
// checks and checksum): the fuzz target (tests/fuzz) feeds it directly, since a mutated file
// almost never passes the checksum. The same checks, the same InputErrors.
SimCheckpoint decode_sim_checkpoint_payload(std::string_view payload, const std::string& name);
SimCheckpoint read_sim_checkpoint(const std::string& path);

}  // namespace hpcplan::io
