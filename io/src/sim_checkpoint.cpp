#include "hpcplan/io/sim_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/status.hpp"

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
// The options that decide a run's result (SimOptions but --runs and the test hooks).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RobotParams, steer_force, max_speed, waypoint_radius)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SafetyParams, robot_radius, particle_radius)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ReactiveParams, horizon_s, margin)
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(SimOptions) == 416 && sizeof(RobotParams) == 24 &&
                  sizeof(SafetyParams) == 16 && sizeof(ReactiveParams) == 16,
              "the simulator's options changed: name the new ones in the checkpoint's key");
#endif
}  // namespace hpcplan::sim

namespace hpcplan::env {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(OccupancyConfig, cell, particle_radius, box_inflation, rule,
                                   density_support, density_threshold)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ParticleWorldConfig, radius)
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(OccupancyConfig) == 48 && sizeof(ParticleWorldConfig) == 8,
              "the worlds' options changed: name the new ones in the checkpoint's key");
#endif
}  // namespace hpcplan::env

namespace hpcplan::plan {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FluidPlanOptions, algo, world, occupancy, particles, seed,
                                   escape_cells, iterations, step, goal_bias, rewire_radius,
                                   goal_radius, time_s)
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(FluidPlanOptions) == 184,
              "the planner's options changed: name the new ones in the checkpoint's key");
#endif
}  // namespace hpcplan::plan

namespace hpcplan::io {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TrajectoryRow, run, frame, t, robot, goal, clearance)
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(TrajectoryRow) == 80, "TrajectoryRow's fields changed: name them above");
#endif

namespace {

constexpr std::string_view kMagic = "hpcplan simulator checkpoint\n";
// Format 2 (issue 46): the runs were made with the robot's particle taken out of the fluid when
// the robot takes its place (sim/simulator.hpp). A format 1 file holds runs made while that
// particle stayed in the fluid, unseen: its records are laid out the same, but a restart from it
// would mix runs of two simulations, so it is refused ("has checkpoint format 1; this hpcplan
// reads format 2").
constexpr std::uint32_t kFormat = 2;

// nlohmann's document builder, refusing nesting deeper than the checkpoint's own (records in
// arrays in the top object, positions in those: 3) as it reads.
class BoundedDepthParser : public nlohmann::detail::json_sax_dom_parser<nlohmann::json> {
 public:
  using Base = nlohmann::detail::json_sax_dom_parser<nlohmann::json>;
  explicit BoundedDepthParser(nlohmann::json& j) : Base(j, false) {}
  bool start_object(std::size_t n) { return enter() && Base::start_object(n); }
  bool end_object() { return leave() && Base::end_object(); }
  bool start_array(std::size_t n) { return enter() && Base::start_array(n); }
  bool end_array() { return leave() && Base::end_array(); }
  bool too_deep() const { return too_deep_; }

 private:
  static constexpr int kMaxDepth = 8;
  bool enter() {
    too_deep_ = too_deep_ || ++depth_ > kMaxDepth;
    return !too_deep_;
  }
  bool leave() {
    --depth_;
    return true;
  }
  int depth_ = 0;
  bool too_deep_ = false;
};

}  // namespace

std::string sim_checkpoint_options(const sim::SimOptions& o, bool trajectory) {
  const nlohmann::json j = {{"scenario", o.scenario},
                            {"particles", o.particles},
                            {"planner", o.planner},
                            {"seed", o.seed},
                            {"pace", o.pace},
                            {"replan_every", o.replan_every},
                            {"lockstep_delay", o.lockstep_delay},
                            {"settle_frames", o.settle_frames},
                            {"max_sim_s", o.max_sim_s},
                            {"max_wall_s", o.max_wall_s},
                            {"goal_radius", o.goal_radius},
                            {"robot", o.robot},
                            {"safety", o.safety},
                            {"controller", o.controller},
                            {"reactive", o.reactive},
                            {"backend", o.backend},
                            {"trajectory", trajectory}};
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
  return decode_sim_checkpoint_payload(
      checkpoint::open(bytes, kMagic, kFormat, "an hpcplan simulator checkpoint", name), name);
}

SimCheckpoint decode_sim_checkpoint_payload(std::string_view payload, const std::string& name) {
  auto damaged = [&](const std::string& what) {
    throw InputError("--restart '" + name + "': " + what + " (damaged)");
  };
  SimCheckpoint c;
  try {
    // The records nest three deep; a deeper document is refused while it is read (the CBOR
    // reader recurses, so a crafted nesting would otherwise exhaust the stack).
    nlohmann::json j;
    BoundedDepthParser sax(j);
    if (!nlohmann::json::sax_parse(payload.begin(), payload.end(), &sax,
                                   nlohmann::json::input_format_t::cbor) ||
        sax.too_deep())
      damaged("holds a payload this hpcplan cannot read");
    c.options = j.at("options").get<std::string>();
    c.result.runs = j.at("runs").get<std::vector<sim::RunRecord>>();
    c.result.replans = j.at("replans").get<std::vector<sim::ReplanRecord>>();
    c.trajectory = j.at("trajectory").get<std::vector<TrajectoryRow>>();
  } catch (const nlohmann::json::exception&) {
    // (A sound checksum over a payload hpcplan cannot read: written by hand, or a bug.)
    damaged("holds a payload this hpcplan cannot read");
  }
  const auto runs = static_cast<int>(c.result.runs.size());
  for (int k = 0; k < runs; ++k) {
    const sim::RunRecord& r = c.result.runs[static_cast<std::size_t>(k)];
    if (r.run_number != k + 1) damaged("holds runs out of order");
    if (sim::to_string(r.end) == "unknown") damaged("holds a run that ended in no known way");
  }
  for (const sim::ReplanRecord& r : c.result.replans)
    if (r.run < 1 || r.run > runs || to_string(r.status) == "unknown" ||
        static_cast<unsigned>(r.blocked) > static_cast<unsigned>(plan::BlockedEnd::goal) ||
        static_cast<unsigned>(r.incremental) > static_cast<unsigned>(plan::Incremental::repair))
      damaged("holds a replan record of no saved run, or of an unknown kind");
  for (const TrajectoryRow& r : c.trajectory)
    if (r.run < 1 || r.run > runs) damaged("holds trajectory rows of no saved run");
  return c;
}

SimCheckpoint read_sim_checkpoint(const std::string& path) {
  return decode_sim_checkpoint(
      checkpoint::read_regular_file(path, kMagic, "an hpcplan simulator checkpoint"), path);
}

}  // namespace hpcplan::io
