#pragma once
// The simulator's results (hpcplan sim): per-run CSV (seed 000's 14 columns first, then the
// ones added here), per-replan CSV, a robot-trajectory CSV, one JSON summary per invocation
// (per-run rows and aggregates) and a readable table.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hpcplan/io/table.hpp"
#include "hpcplan/sim/simulator.hpp"

namespace hpcplan::io {

struct SimInvocation {
  sim::SimOptions options;
  int threads = 1;
  sim::SimResult result;
  double seconds = 0.0;
  // result.interrupted: the signal that asked it to end, and the checkpoint holding the runs
  // finished before ("" without --checkpoint).
  std::string interrupted_by, checkpoint;
};

// The per-run rows (seed 000's 14 columns first, then hpcplan's) and the per-replan rows.
// `timings`: false leaves the timing cells empty, so that two lockstep runs with the same seed
// give identical rows.
Table sim_runs_table(const std::vector<sim::RunRecord>& runs, bool timings = true);
Table sim_replans_table(const std::vector<sim::ReplanRecord>& replans, bool timings = true);

// Their CSV text (to_csv): header + one row per run. `timings`: false writes timing columns as empty, so that two
// lockstep runs with the same seed give identical bytes.
std::string sim_runs_csv(const std::vector<sim::RunRecord>& runs, bool header = true,
                         bool timings = true);
std::string sim_replans_csv(const std::vector<sim::ReplanRecord>& replans, bool timings = true);
nlohmann::json to_json(const SimInvocation& s);
std::string to_summary(const SimInvocation& s);

// run,frame,t,robot_x,robot_y,robot_z,goal_x,goal_y,goal_z,clearance (17 significant digits;
// clearance: the robot's this frame, negative in contact, see sim/safety.hpp).
struct TrajectoryRow {
  int run;
  std::uint64_t frame;
  double t;
  env::Vec<3> robot, goal;
  double clearance;
};
std::string trajectory_csv(const std::vector<TrajectoryRow>& rows);

}  // namespace hpcplan::io
