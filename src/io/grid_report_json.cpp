#include "hpcplan/io/grid_report_json.hpp"

#include <cstdio>
#include <sstream>

#include "hpcplan/core/format.hpp"

namespace hpcplan {

nlohmann::json to_json(const GridReport& r, bool include_path) {
  nlohmann::json j;
  j["status"] = std::string(search::to_string(r.status));
  j["dims"] = r.dims;
  j["algo"] = r.algorithm;
  j["weight"] = r.weight;
  j["heuristic"] = r.heuristic;
  j["connectivity"] = r.connectivity;
  j["seed"] = r.seed;
  j["extent"] = r.extent;
  j["threshold"] = r.threshold;
  j["gog_shift_p"] = r.shift_p;
  j["gog_shift_v"] = r.shift_v;
  j["blocked_fraction"] = r.blocked_fraction;
  j["start"] = r.start;
  j["goal"] = r.goal;
  j["start_adjusted"] = r.start_adjusted;
  j["goal_adjusted"] = r.goal_adjusted;
  const bool solved = r.status == search::Status::solved;
  // Unsolved runs have no cost: null rather than a misleading 0.
  j["cost"] = solved ? nlohmann::json(r.cost) : nlohmann::json(nullptr);
  j["hops"] = solved ? nlohmann::json(r.hops) : nlohmann::json(nullptr);
  j["quality"] = solved ? nlohmann::json(r.quality) : nlohmann::json(nullptr);
  j["straight_line"] = r.straight_line;
  j["expanded"] = r.counters.expanded;
  j["generated"] = r.counters.generated;
  j["reopened"] = r.counters.reopened;
  j["collision_checks"] = r.counters.collision_checks;
  j["peak_states"] = r.counters.peak_states;
  j["peak_open"] = r.counters.peak_open;
  j["max_states"] = r.max_states;
  j["time_ms"] = r.counters.time_ms;
  j["setup_ms"] = r.setup_ms;
  j["ranks"] = r.ranks;
  j["key_words"] = r.key_words;
  j["visited_map"] = r.visited_map;
  if (include_path) j["path"] = r.path;
  return j;
}

std::string to_summary(const GridReport& r) {
  auto coords = [](const std::vector<int>& s) {
    return std::string("(").append(join_coordinates(s)).append(")");
  };
  std::ostringstream o;
  char line[256];
  o << "hpcplan grid: " << r.algorithm << " in " << r.dims << "D, extent " << r.extent << ", seed "
    << r.seed << ", " << r.ranks << " rank(s)\n";
  std::snprintf(line, sizeof line, "  field      threshold %d, %.1f%% of states blocked\n",
                r.threshold, 100.0 * r.blocked_fraction);
  o << line;
  o << "  start      " << coords(r.start) << (r.start_adjusted ? " (adjusted)" : "") << "\n";
  o << "  goal       " << coords(r.goal) << (r.goal_adjusted ? " (adjusted)" : "") << "\n";
  o << "  status     " << search::to_string(r.status) << "\n";
  if (r.status == search::Status::solved) {
    std::snprintf(line, sizeof line, "  cost       %.4f over %llu moves, quality %.4f\n", r.cost,
                  static_cast<unsigned long long>(r.hops), r.quality);
    o << line;
  }
  std::snprintf(line, sizeof line,
                "  work       %llu expanded, %llu generated, %llu collision checks, %llu stored\n",
                static_cast<unsigned long long>(r.counters.expanded),
                static_cast<unsigned long long>(r.counters.generated),
                static_cast<unsigned long long>(r.counters.collision_checks),
                static_cast<unsigned long long>(r.counters.peak_states));
  o << line;
  std::snprintf(line, sizeof line, "  time       %.3f ms search, %.3f ms set-up\n",
                r.counters.time_ms, r.setup_ms);
  o << line;
  if (!r.path.empty()) {
    o << "  path      ";
    for (const auto& s : r.path) o << " " << coords(s);
    o << "\n";
  }
  return o.str();
}

}  // namespace hpcplan
