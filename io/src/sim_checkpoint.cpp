#include "hpcplan/io/sim_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/error.hpp"

// The records' fields, each named once for both directions (enums as their numbers). A field
// added to a record and not here is lost across a restart: tests/sim/test_sim_cli.sh compares
// every CSV and JSON figure of a restarted invocation with the uninterrupted one's.
namespace hpcplan::sim {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ReplanRecord, run, frame, sim_time_s, algorithm, status, blocked,
                                   plan_us, world_us, search_us, smooth_us, expanded, length,
                                   waypoints, divergence, start_escaped, goal_escaped, incremental)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(
    RunRecord, scenario, algorithm, pace, run_number, seed, particle_count, end, sim_time_s,
    wall_time_s, frames, total_replans, failed_replans, start_blocked, goal_blocked, disconnected,
    budget, cancelled, start_escapes, goal_escapes, avg_plan_time_us, min_plan_time_us,
    max_plan_time_us, p50_plan_time_us, p95_plan_time_us, p99_plan_time_us, avg_path_length,
    seed_avg_path_length, avg_path_nodes, avg_path_divergence, sph_ms_per_frame, snapshot_ms,
    distance_travelled, start_goal_distance, controller, occupancy, contacts, contact_frames,
    contact_time_s, min_clearance, max_overlap, reactive_overrides)
// A tripwire where it can be exact (x86-64, libstdc++): a field added to a record changes its
// size; add it to the list above, then update the size here.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(ReplanRecord) == 136 && sizeof(RunRecord) == 448,
              "a record's fields changed: name them in NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE above");
#endif
}  // namespace hpcplan::sim

namespace hpcplan::io {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TrajectoryRow, run, frame, t, robot, goal, clearance)
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(TrajectoryRow) == 80, "TrajectoryRow's fields changed: name them above");
#endif

namespace {

constexpr std::string_view kMagic = "hpcplan simulator checkpoint\n";
constexpr std::uint32_t kFormat = 1;

}  // namespace

std::string sim_checkpoint_options(const sim::SimOptions& options, int threads) {
  SimInvocation inv;
  inv.options = options;
  inv.threads = threads;
  nlohmann::json j = to_json(inv);
  for (const char* key : {"runs_requested", "seconds", "runs", "aggregate"}) j.erase(key);
  return j.dump();
}

std::string encode_sim_checkpoint(const SimCheckpoint& c) {
  const nlohmann::json j = {{"options", c.options},
                            {"runs", c.result.runs},
                            {"replans", c.result.replans},
                            {"trajectory", c.trajectory}};
  const std::vector<std::uint8_t> cbor = nlohmann::json::to_cbor(j);
  return checkpoint::seal(
      kMagic, kFormat, std::string_view(reinterpret_cast<const char*>(cbor.data()), cbor.size()));
}

SimCheckpoint decode_sim_checkpoint(std::string_view bytes, const std::string& name) {
  const std::string_view payload =
      checkpoint::open(bytes, kMagic, kFormat, "an hpcplan simulator checkpoint", name);
  SimCheckpoint c;
  try {
    const nlohmann::json j = nlohmann::json::from_cbor(payload);
    c.options = j.at("options").get<std::string>();
    c.result.runs = j.at("runs").get<std::vector<sim::RunRecord>>();
    c.result.replans = j.at("replans").get<std::vector<sim::ReplanRecord>>();
    c.trajectory = j.at("trajectory").get<std::vector<TrajectoryRow>>();
  } catch (const nlohmann::json::exception&) {
    // (A sound checksum over a payload hpcplan cannot read: written by hand, or a bug.)
    throw InputError("--restart '" + name + "': holds a payload this hpcplan cannot read");
  }
  for (std::size_t k = 0; k < c.result.runs.size(); ++k)
    if (c.result.runs[k].run_number != static_cast<int>(k + 1))
      throw InputError("--restart '" + name + "': holds runs out of order (damaged)");
  return c;
}

SimCheckpoint read_sim_checkpoint(const std::string& path) {
  return decode_sim_checkpoint(checkpoint::read_regular_file(path), path);
}

}  // namespace hpcplan::io
