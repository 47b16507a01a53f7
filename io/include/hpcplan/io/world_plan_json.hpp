#pragma once
// A plan in a continuous world (hpcplan map3d / sphere2d, the world sweep) as JSON and as a
// readable summary: the documented keys of README.md.
#include <cstdio>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "hpcplan/plan/world_planner.hpp"

namespace hpcplan {

template <int D>
nlohmann::json to_json(const plan::WorldPlan<D>& p) {
  nlohmann::json path = nlohmann::json::array();
  for (const auto& q : p.path) path.push_back(q);
  nlohmann::json j = {{"status", to_string(p.status)},
                      {"algo", p.algo},
                      {"length", p.cost},
                      {"raw_length", p.raw_cost},
                      {"time_ms", p.counters.time_ms},
                      {"plan_ms", p.plan_ms},
                      {"expanded", p.counters.expanded},
                      {"tree_size", p.counters.peak_states},
                      {"collision_checks", p.counters.collision_checks},
                      {"waypoints", p.path.size()},
                      {"path", path}};
  if (p.counters.first_solution_ms >= 0) j["first_solution_ms"] = p.counters.first_solution_ms;
  if (p.counters.samples > 0) j["samples"] = p.counters.samples;
  return j;
}

// `map`: the world file's name, shown first.
template <int D>
std::string to_summary(const plan::WorldPlan<D>& p, const std::string& map) {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "%-18s %s\n", "map", map.c_str());
  s += buf;
  const std::pair<const char*, std::string> rows[] = {
      {"algorithm", p.algo},
      {"status", std::string(to_string(p.status))},
      {"length", std::to_string(p.cost)},
      {"as planned", std::to_string(p.raw_cost)},
      {"waypoints", std::to_string(p.path.size())},
      {"time (ms)", std::to_string(p.counters.time_ms)},
      {"expanded", std::to_string(p.counters.expanded)},
      {"tree / stored", std::to_string(p.counters.peak_states)},
      {"collision checks", std::to_string(p.counters.collision_checks)},
  };
  for (const auto& [k, v] : rows) {
    std::snprintf(buf, sizeof buf, "%-18s %s\n", k, v.c_str());
    s += buf;
  }
  return s;
}

// The world sweep's CSV (bench/world_sweep.cpp): the header, and one row per run.
inline std::string world_plan_csv_header() {
  return "map,config,run,status,length,raw_length,time_ms,plan_ms,first_ms,expanded,tree_size,"
         "checks\n";
}

template <int D>
std::string to_csv_row(const plan::WorldPlan<D>& p, const std::string& map,
                       const std::string& config, int run) {
  char row[512];
  std::snprintf(row, sizeof row, "%s,%s,%d,%s,%.9f,%.9f,%.4f,%.4f,%.4f,%llu,%llu,%llu\n",
                map.c_str(), config.c_str(), run, std::string(to_string(p.status)).c_str(), p.cost,
                p.raw_cost, p.counters.time_ms, p.plan_ms, p.counters.first_solution_ms,
                static_cast<unsigned long long>(p.counters.expanded),
                static_cast<unsigned long long>(p.counters.peak_states),
                static_cast<unsigned long long>(p.counters.collision_checks));
  return row;
}

}  // namespace hpcplan
