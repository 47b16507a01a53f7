#include "hpcplan/sim/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hpcplan::sim {

namespace {
double distance_to_polyline(const std::vector<env::Vec<3>>& path, const env::Vec<3>& p) {
  if (path.size() == 1) return env::distance<3>(path[0], p);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < path.size(); ++i) {
    const env::Vec<3>& a = path[i - 1];
    const env::Vec<3>& b = path[i];
    double ab2 = 0.0, t = 0.0;
    for (int k = 0; k < 3; ++k) {
      ab2 += (b[k] - a[k]) * (b[k] - a[k]);
      t += (b[k] - a[k]) * (p[k] - a[k]);
    }
    t = ab2 > 0.0 ? std::clamp(t / ab2, 0.0, 1.0) : 0.0;
    best = std::min(best, env::distance<3>(env::lerp<3>(a, b, t), p));
  }
  return best;
}
}  // namespace

double divergence(const std::vector<env::Vec<3>>& previous, const std::vector<env::Vec<3>>& path) {
  if (previous.empty() || path.empty()) return 0.0;
  constexpr double kSpacing = 0.05;
  double sum = 0.0;
  std::size_t samples = 0;
  auto add = [&](const env::Vec<3>& p) {
    sum += distance_to_polyline(previous, p);
    ++samples;
  };
  add(path.front());
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double len = env::distance<3>(path[i - 1], path[i]);
    const int pieces = std::max(1, static_cast<int>(std::ceil(len / kSpacing)));
    for (int j = 1; j < pieces; ++j) add(env::lerp<3>(path[i - 1], path[i], double(j) / pieces));
    add(path[i]);
  }
  return sum / static_cast<double>(samples);
}

std::string_view to_string(RunEnd e) {
  switch (e) {
    case RunEnd::goal_reached:
      return "goal_reached";
    case RunEnd::sim_time_cap:
      return "sim_time_cap";
    case RunEnd::wall_time_cap:
      return "wall_time_cap";
    case RunEnd::fluid_unstable:
      return "fluid_unstable";
  }
  return "unknown";
}

double quantile(std::vector<double> xs, double q) {
  if (xs.empty()) return 0.0;
  std::sort(xs.begin(), xs.end());
  const double pos = q * static_cast<double>(xs.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(pos));
  const double frac = pos - static_cast<double>(i);
  return i + 1 < xs.size() ? xs[i] + frac * (xs[i + 1] - xs[i]) : xs[i];
}

void summarise_replans(RunRecord& run, const std::vector<ReplanRecord>& replans) {
  std::vector<double> times;
  double length = 0.0, nodes = 0.0, div = 0.0;
  std::uint64_t solved = 0, compared = 0;
  for (const ReplanRecord& r : replans) {
    if (r.run != run.run_number) continue;
    if (r.status == Status::cancelled) {  // ended with the run, never used: not an answer
      ++run.cancelled;
      continue;
    }
    ++run.total_replans;
    times.push_back(r.plan_us);
    run.start_escapes += r.start_escaped;
    run.goal_escapes += r.goal_escaped;
    if (!r.solved()) {
      ++run.failed_replans;
      if (r.status == Status::no_path)
        ++(r.blocked == plan::BlockedEnd::start  ? run.start_blocked
           : r.blocked == plan::BlockedEnd::goal ? run.goal_blocked
                                                 : run.disconnected);
      else
        ++run.budget;  // budget_exceeded or timeout
      continue;
    }
    ++solved;
    length += r.length;
    nodes += static_cast<double>(r.waypoints);
    if (r.divergence >= 0.0) div += r.divergence, ++compared;
  }
  if (!times.empty()) {
    double sum = 0.0;
    for (double t : times) sum += t;
    run.avg_plan_time_us = sum / static_cast<double>(times.size());
    run.min_plan_time_us = *std::min_element(times.begin(), times.end());
    run.max_plan_time_us = *std::max_element(times.begin(), times.end());
    run.p50_plan_time_us = quantile(times, 0.50);
    run.p95_plan_time_us = quantile(times, 0.95);
    run.p99_plan_time_us = quantile(times, 0.99);
  }
  run.avg_path_length = solved ? length / static_cast<double>(solved) : 0.0;
  run.seed_avg_path_length =
      run.total_replans ? length / static_cast<double>(run.total_replans) : 0.0;
  run.avg_path_nodes = solved ? nodes / static_cast<double>(solved) : 0.0;
  run.avg_path_divergence = compared ? div / static_cast<double>(compared) : 0.0;
}

}  // namespace hpcplan::sim
