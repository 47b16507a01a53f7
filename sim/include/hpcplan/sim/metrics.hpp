#pragma once
// What a run records: one row per replan and one per run, with seed 000's columns and the ones
// its published figures could not tell apart (simulated and wall time, plan-time percentiles,
// why replans failed, the escapes from blocked ends).
//
// Divergence (the seed's "mean distance between consecutive planned paths"): the new path is
// sampled every 0.05 along its length, both ends included, and each sample's distance to the
// nearest point of the previous path (the polyline, exactly) is averaged. Only consecutive
// successful plans are compared; a run's divergence is the mean over those pairs.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/core/status.hpp"
#include "hpcplan/env/point.hpp"
#include "hpcplan/plan/fluid_planner.hpp"

namespace hpcplan::sim {

struct ReplanRecord {
  int run = 0;
  std::uint64_t frame = 0;  // when it was launched
  double sim_time_s = 0.0;  // ... in simulated seconds
  std::string algorithm;
  Status status = Status::no_path;  // how the replan ended
  plan::BlockedEnd blocked = plan::BlockedEnd::none;
  double plan_us = 0.0;  // the whole replan: world, search, smoothing
  double world_us = 0.0, search_us = 0.0, smooth_us = 0.0;
  std::uint64_t expanded = 0;
  double length = 0.0;
  std::size_t waypoints = 0;
  double divergence = -1.0;  // -1: no previous successful plan to compare with
  bool start_escaped = false, goal_escaped = false;
  plan::Incremental incremental = plan::Incremental::none;  // dstar_lite
  bool solved() const { return status == Status::solved; }
  // The seed's failure category (plan::failure_reason): empty when solved.
  std::string_view reason() const { return plan::failure_reason(status, blocked); }
};

// How a run ended.
enum class RunEnd { goal_reached, sim_time_cap, wall_time_cap, fluid_unstable };
std::string_view to_string(RunEnd e);

struct RunRecord {
  std::string scenario, algorithm, pace;
  int run_number = 0;
  std::uint64_t seed = 0;
  std::size_t particle_count = 0;
  RunEnd end = RunEnd::sim_time_cap;
  bool success() const { return end == RunEnd::goal_reached; }
  double sim_time_s = 0.0;   // simulated seconds until the goal (or the cap)
  double wall_time_s = 0.0;  // wall seconds of the replanning loop
  std::uint64_t frames = 0;
  std::uint64_t total_replans = 0, failed_replans = 0;
  std::uint64_t start_blocked = 0, goal_blocked = 0, disconnected = 0, budget = 0, cancelled = 0;
  std::uint64_t start_escapes = 0, goal_escapes = 0;
  double avg_plan_time_us = 0.0, min_plan_time_us = 0.0, max_plan_time_us = 0.0;
  double p50_plan_time_us = 0.0, p95_plan_time_us = 0.0, p99_plan_time_us = 0.0;
  double avg_path_length = 0.0;       // over successful replans only
  double seed_avg_path_length = 0.0;  // the seed's: total length over all replans
  double avg_path_nodes = 0.0;        // waypoints, successful replans
  double avg_path_divergence = 0.0;
  double sph_ms_per_frame = 0.0;  // median
  double snapshot_ms = 0.0;       // median, per replan
  double distance_travelled = 0.0;
  double start_goal_distance = 0.0;
  // Safety (safety.hpp), over the frames after the robot was placed.
  std::string controller;  // seed or reactive
  std::string occupancy;   // the grid planners' occupancy: env::occupancy_label
  std::uint64_t contacts = 0, contact_frames = 0;
  double contact_time_s = 0.0;
  double min_clearance = 0.0;            // over the run's frames (+infinity: no obstacle at all)
  double max_overlap = 0.0;              // deepest overlap, >= 0
  std::uint64_t reactive_overrides = 0;  // frames where the reactive layer changed the velocity
  double contact_rate() const {
    return frames ? static_cast<double>(contact_frames) / static_cast<double>(frames) : 0.0;
  }
};

// The divergence of `path` from `previous` as defined above (0 when either is empty).
double divergence(const std::vector<env::Vec<3>>& previous, const std::vector<env::Vec<3>>& path);

// The q-quantile (0..1) of xs by linear interpolation; 0 for an empty list.
double quantile(std::vector<double> xs, double q);

// Fills the aggregate fields of `run` from its replans.
void summarise_replans(RunRecord& run, const std::vector<ReplanRecord>& replans);

}  // namespace hpcplan::sim
