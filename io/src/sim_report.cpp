#include "hpcplan/io/sim_report.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <map>

namespace hpcplan::io {

namespace {

std::string num(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double mean(const std::vector<double>& xs) {
  double s = 0.0;
  for (double x : xs) s += x;
  return xs.empty() ? 0.0 : s / static_cast<double>(xs.size());
}

}  // namespace

Table sim_runs_table(const std::vector<sim::RunRecord>& runs, bool timings) {
  Table t;
  t.columns = {"scenario",
               "algorithm",
               "run_number",
               "success",
               "time_to_goal_s",
               "total_replans",
               "failed_replans",
               "avg_plan_time_us",
               "min_plan_time_us",
               "max_plan_time_us",
               "avg_path_length",
               "avg_path_nodes",
               "avg_path_divergence",
               "particle_count",
               "contacts",
               "contact_frames",
               "contact_time_s",
               "min_clearance",
               "max_overlap",
               "seed_avg_path_length",
               "sim_time_to_goal_s",
               "wall_time_to_goal_s",
               "p50_plan_time_us",
               "p95_plan_time_us",
               "p99_plan_time_us",
               "end",
               "fail_start_blocked",
               "fail_goal_blocked",
               "fail_disconnected",
               "fail_budget",
               "cancelled",
               "start_escapes",
               "goal_escapes",
               "sph_ms_per_frame",
               "snapshot_ms",
               "frames",
               "distance_travelled",
               "start_goal_distance",
               "seed",
               "pace",
               "controller",
               "contact_rate",
               "reactive_overrides",
               "occupancy"};
  // A timing column is empty without timings, so that lockstep files compare byte for byte.
  auto time = [&](double v) { return timings ? Cell(v) : Cell(); };
  for (const sim::RunRecord& r : runs)
    t.rows.push_back({r.scenario,
                      r.algorithm,
                      whole(r.run_number),
                      whole(r.success() ? 1 : 0),
                      r.sim_time_s,
                      whole(r.total_replans),
                      whole(r.failed_replans),
                      time(r.avg_plan_time_us),
                      time(r.min_plan_time_us),
                      time(r.max_plan_time_us),
                      r.avg_path_length,
                      r.avg_path_nodes,
                      r.avg_path_divergence,
                      whole(r.particle_count),
                      whole(r.contacts),
                      whole(r.contact_frames),
                      r.contact_time_s,
                      r.min_clearance,
                      r.max_overlap,
                      r.seed_avg_path_length,
                      r.success() ? Cell(r.sim_time_s) : Cell(),
                      r.success() ? time(r.wall_time_s) : Cell(),
                      time(r.p50_plan_time_us),
                      time(r.p95_plan_time_us),
                      time(r.p99_plan_time_us),
                      std::string(sim::to_string(r.end)),
                      whole(r.start_blocked),
                      whole(r.goal_blocked),
                      whole(r.disconnected),
                      whole(r.budget),
                      whole(r.cancelled),
                      whole(r.start_escapes),
                      whole(r.goal_escapes),
                      time(r.sph_ms_per_frame),
                      time(r.snapshot_ms),
                      whole(r.frames),
                      r.distance_travelled,
                      r.start_goal_distance,
                      whole(r.seed),
                      r.pace,
                      r.controller,
                      r.contact_rate(),
                      whole(r.reactive_overrides),
                      r.occupancy});
  return t;
}

Table sim_replans_table(const std::vector<sim::ReplanRecord>& replans, bool timings) {
  Table t;
  t.columns = {"run",       "frame",     "sim_time_s",    "algorithm",    "status",     "reason",
               "plan_us",   "expanded",  "length",        "waypoints",    "divergence", "world_us",
               "search_us", "smooth_us", "start_escaped", "goal_escaped", "incremental"};
  auto time = [&](double v) { return timings ? Cell(v) : Cell(); };
  for (const sim::ReplanRecord& r : replans)
    t.rows.push_back({whole(r.run), whole(r.frame), r.sim_time_s, r.algorithm,
                      std::string(to_string(r.status)), std::string(r.reason()), time(r.plan_us),
                      whole(r.expanded), r.length, whole(r.waypoints),
                      r.divergence >= 0 ? Cell(r.divergence) : Cell(), time(r.world_us),
                      time(r.search_us), time(r.smooth_us), whole(r.start_escaped ? 1 : 0),
                      whole(r.goal_escaped ? 1 : 0), std::string(plan::to_string(r.incremental))});
  return t;
}

std::string sim_runs_csv(const std::vector<sim::RunRecord>& runs, bool header, bool timings) {
  return to_csv(sim_runs_table(runs, timings), header);
}

std::string sim_replans_csv(const std::vector<sim::ReplanRecord>& replans, bool timings) {
  return to_csv(sim_replans_table(replans, timings));
}

nlohmann::json to_json(const SimInvocation& s) {
  const sim::SimOptions& o = s.options;
  nlohmann::json j;
  j["scenario"] = std::string(sph::to_string(o.scenario));
  j["algorithm"] = o.planner.algo;
  j["particles"] = o.particles;
  j["runs_requested"] = o.runs;
  j["seed"] = o.seed;
  j["pace"] = std::string(sim::to_string(o.pace));
  j["controller"] = std::string(sim::to_string(o.controller));
  j["robot_radius"] = o.safety.robot_radius;
  j["particle_radius"] = o.safety.particle_radius;
  if (o.controller == sim::Controller::reactive)
    j["reactive"] = {{"horizon_s", o.reactive.horizon_s}, {"margin", o.reactive.margin}};
  {
    const env::OccupancyConfig& g = o.planner.occupancy;
    j["occupancy"] = {{"rule", std::string(env::to_string(g.rule))}, {"cell", g.cell}};
    if (g.rule == env::OccupancyRule::density) {
      j["occupancy"]["density_support"] = g.density_support;
      j["occupancy"]["density_threshold"] = g.density_threshold;
    } else {
      j["occupancy"]["particle_radius"] = g.particle_radius;
    }
  }
  j["replan_every"] = o.replan_every;
  j["settle_frames"] = sim::settle_frames(o);
  j["max_sim_s"] = o.max_sim_s;
  j["max_wall_s"] = o.max_wall_s;
  j["threads"] = s.threads;
  j["backend"] = o.backend;
  j["seconds"] = s.seconds;
  j["status"] = s.result.interrupted ? "interrupted" : "ok";
  if (s.result.interrupted) {
    j["interrupted_by"] = s.interrupted_by;
    j["checkpoint"] = s.checkpoint;
  }
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> ttg, plan, plan_p50, plan_p99, fail_rate, lengths, sph_ms;
  std::uint64_t successes = 0, replans = 0, failed = 0, escapes = 0;
  std::vector<double> contact_rates;
  std::uint64_t contacts = 0, contact_frames = 0, frames = 0;
  double max_overlap = 0.0;
  for (const sim::RunRecord& r : s.result.runs) {
    nlohmann::json row;
    row["run_number"] = r.run_number;
    row["success"] = r.success();
    row["end"] = std::string(sim::to_string(r.end));
    row["time_to_goal_s"] = r.sim_time_s;
    row["wall_time_s"] = r.wall_time_s;
    row["frames"] = r.frames;
    row["total_replans"] = r.total_replans;
    row["failed_replans"] = r.failed_replans;
    row["failures"] = {{"start_blocked", r.start_blocked},
                       {"goal_blocked", r.goal_blocked},
                       {"disconnected", r.disconnected},
                       {"budget", r.budget}};
    row["cancelled"] = r.cancelled;
    row["start_escapes"] = r.start_escapes;
    row["goal_escapes"] = r.goal_escapes;
    row["plan_time_us"] = {{"mean", r.avg_plan_time_us}, {"min", r.min_plan_time_us},
                           {"max", r.max_plan_time_us},  {"p50", r.p50_plan_time_us},
                           {"p95", r.p95_plan_time_us},  {"p99", r.p99_plan_time_us}};
    row["avg_path_length"] = r.avg_path_length;
    row["seed_avg_path_length"] = r.seed_avg_path_length;
    row["avg_path_nodes"] = r.avg_path_nodes;
    row["avg_path_divergence"] = r.avg_path_divergence;
    row["particle_count"] = r.particle_count;
    row["sph_ms_per_frame"] = r.sph_ms_per_frame;
    row["snapshot_ms"] = r.snapshot_ms;
    row["distance_travelled"] = r.distance_travelled;
    row["start_goal_distance"] = r.start_goal_distance;
    row["safety"] = {{"contacts", r.contacts},
                     {"contact_frames", r.contact_frames},
                     {"contact_time_s", r.contact_time_s},
                     {"contact_rate", r.contact_rate()},
                     {"min_clearance", finite_or_null(r.min_clearance)},
                     {"max_overlap", r.max_overlap},
                     {"reactive_overrides", r.reactive_overrides}};
    rows.push_back(row);
    contact_rates.push_back(r.contact_rate());
    contacts += r.contacts;
    contact_frames += r.contact_frames;
    frames += r.frames;
    max_overlap = std::max(max_overlap, r.max_overlap);
    if (r.success()) ++successes, ttg.push_back(r.sim_time_s);
    replans += r.total_replans;
    failed += r.failed_replans;
    escapes += r.start_escapes;
    plan.push_back(r.avg_plan_time_us);
    plan_p50.push_back(r.p50_plan_time_us);
    plan_p99.push_back(r.p99_plan_time_us);
    if (r.total_replans) fail_rate.push_back(double(r.failed_replans) / double(r.total_replans));
    if (r.avg_path_length > 0) lengths.push_back(r.avg_path_length);
    sph_ms.push_back(r.sph_ms_per_frame);
  }
  j["runs"] = rows;
  // Plan-time percentiles over every replan of the invocation.
  std::vector<double> all;
  for (const sim::ReplanRecord& r : s.result.replans)
    if (r.status != Status::cancelled) all.push_back(r.plan_us);
  j["aggregate"] = {
      {"runs", s.result.runs.size()},
      {"successes", successes},
      {"success_rate",
       s.result.runs.empty() ? 0.0 : double(successes) / double(s.result.runs.size())},
      {"time_to_goal_s_mean", mean(ttg)},
      {"total_replans", replans},
      {"failed_replans", failed},
      {"failed_replan_rate", replans ? double(failed) / double(replans) : 0.0},
      {"start_escapes", escapes},
      {"plan_time_us_mean", mean(all)},
      {"plan_time_us_p50", sim::quantile(all, 0.5)},
      {"plan_time_us_p95", sim::quantile(all, 0.95)},
      {"plan_time_us_p99", sim::quantile(all, 0.99)},
      {"avg_path_length", mean(lengths)},
      {"sph_ms_per_frame_median", sim::quantile(sph_ms, 0.5)},
      // Contact rate: frames in contact / frames, per run; and over every frame of every run.
      {"contact_rate_mean", mean(contact_rates)},
      {"contact_rate_p50", sim::quantile(contact_rates, 0.5)},
      {"contact_rate_p95", sim::quantile(contact_rates, 0.95)},
      {"contact_rate_max", sim::quantile(contact_rates, 1.0)},
      {"contact_rate_all_frames", frames ? double(contact_frames) / double(frames) : 0.0},
      {"contacts", contacts},
      {"max_overlap", max_overlap},
  };
  return j;
}

std::string to_summary(const SimInvocation& s) {
  const nlohmann::json j = to_json(s);
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line,
                "hpcplan sim: %s, %s, %zu particles, %s pacing, %s controller, seed %" PRIu64
                ", %d thread(s)\n",
                j["scenario"].get<std::string>().c_str(), j["algorithm"].get<std::string>().c_str(),
                s.options.particles, j["pace"].get<std::string>().c_str(),
                j["controller"].get<std::string>().c_str(), s.options.seed, s.threads);
  out += line;
  out +=
      "run  result        t_goal(s)  replans  failed  plan p50(ms)  p99(ms)  path len  escapes"
      "  contacts  contact%  min clear\n";
  for (const sim::RunRecord& r : s.result.runs) {
    std::snprintf(line, sizeof line,
                  "%3d  %-12s  %9.2f  %7" PRIu64 "  %6" PRIu64 "  %12.3f  %7.3f  %8.2f  %7" PRIu64
                  "  %8" PRIu64 "  %8.2f  %9.3f\n",
                  r.run_number, std::string(sim::to_string(r.end)).c_str(), r.sim_time_s,
                  r.total_replans, r.failed_replans, r.p50_plan_time_us / 1e3,
                  r.p99_plan_time_us / 1e3, r.avg_path_length, r.start_escapes, r.contacts,
                  100.0 * r.contact_rate(), r.min_clearance);
    out += line;
  }
  const auto& a = j["aggregate"];
  std::snprintf(
      line, sizeof line,
      "reached the goal in %d of %zu runs; failed replans %.1f%%; plan time p50 %.3f ms, "
      "p99 %.3f ms; fluid %.2f ms/frame (median); frames in contact %.2f%% (robot radius "
      "%.3g, particle radius %.3g)\n",
      a["successes"].get<int>(), s.result.runs.size(),
      100.0 * a["failed_replan_rate"].get<double>(), a["plan_time_us_p50"].get<double>() / 1e3,
      a["plan_time_us_p99"].get<double>() / 1e3, a["sph_ms_per_frame_median"].get<double>(),
      100.0 * a["contact_rate_all_frames"].get<double>(), s.options.safety.robot_radius,
      s.options.safety.particle_radius);
  out += line;
  if (s.result.interrupted)
    out += "interrupted by " + s.interrupted_by + " after " + std::to_string(s.result.runs.size()) +
           " run(s)" +
           (s.checkpoint.empty() ? std::string(" (no --checkpoint: nothing to restart from)\n")
                                 : "; continue with --restart " + s.checkpoint + "\n");
  return out;
}

std::string trajectory_csv(const std::vector<TrajectoryRow>& rows) {
  std::string out = "run,frame,t,robot_x,robot_y,robot_z,goal_x,goal_y,goal_z,clearance\n";
  for (const TrajectoryRow& r : rows) {
    out += std::to_string(r.run) + "," + std::to_string(r.frame) + "," + num(r.t, 17);
    for (double v : r.robot) out.append(",").append(num(v, 17));
    for (double v : r.goal) out.append(",").append(num(v, 17));
    out.append(",").append(num(r.clearance, 17)).append("\n");
  }
  return out;
}

}  // namespace hpcplan::io
