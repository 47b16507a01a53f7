#include "hpcplan/io/scenario_report.hpp"

#include <cstdio>
#include <sstream>

namespace hpcplan {

std::string scenario_csv(const std::vector<ScenarioRowResult>& rows, int dims) {
  static const char* kAxes[] = {"x", "y", "z"};
  std::string out = "row,bucket";
  for (const char* end : {"start", "goal"})
    for (int a = 0; a < dims; ++a)
      out.append(",").append(end).append("_").append(a < 3 ? std::string(kAxes[a])
                                                           : std::to_string(a));
  out += ",optimal,cost,status,expanded,hops,time_us,mismatch\n";
  char line[128];
  for (const ScenarioRowResult& r : rows) {
    out.append(std::to_string(r.row)).append(",").append(std::to_string(r.bucket));
    for (int c : r.start) out.append(",").append(std::to_string(c));
    for (int c : r.goal) out.append(",").append(std::to_string(c));
    std::snprintf(line, sizeof line, ",%.8f,%.8f,", r.optimal, r.cost);
    out += line;
    out += std::string(to_string(r.status));
    std::snprintf(line, sizeof line, ",%llu,%llu,%.3f,%d\n",
                  static_cast<unsigned long long>(r.expanded),
                  static_cast<unsigned long long>(r.hops), r.time_us, r.mismatch ? 1 : 0);
    out += line;
  }
  return out;
}

nlohmann::json to_json(const ScenarioRunInfo& info, const ScenarioSummary& s) {
  nlohmann::json j;
  j["scenario"] = info.scenario;
  j["map"] = info.map;
  j["format"] = info.format;
  j["shape"] = info.shape;
  j["algo"] = info.algorithm;
  j["weight"] = info.weight;
  j["engine"] = info.engine;
  j["connectivity"] = info.connectivity;
  j["ranks"] = info.ranks;
  j["split"] = info.split;
  j["file_rows"] = info.file_rows;
  if (!info.interrupted_by.empty()) j["interrupted_by"] = info.interrupted_by;
  j["rows"] = s.rows;
  j["solved"] = s.solved;
  j["mismatches"] = s.mismatches;
  j["mismatch_rows"] = s.mismatch_rows;
  j["load_ms"] = info.load_ms;
  j["wall_ms"] = info.wall_ms;
  j["query_us"] = {{"total", s.total_us}, {"p50", s.p50_us}, {"p95", s.p95_us}, {"max", s.max_us}};
  j["expanded"] = s.expanded;
  j["states_per_second"] = s.states_per_second;
  nlohmann::json buckets = nlohmann::json::array();
  for (const BucketTimes& b : s.buckets)
    buckets.push_back({{"bucket", b.bucket},
                       {"rows", b.rows},
                       {"mismatches", b.mismatches},
                       {"p50_us", b.p50_us},
                       {"p95_us", b.p95_us},
                       {"max_us", b.max_us},
                       {"mean_expanded", b.mean_expanded}});
  j["buckets"] = std::move(buckets);
  return j;
}

std::string to_summary(const ScenarioRunInfo& info, const ScenarioSummary& s) {
  std::ostringstream o;
  char line[256];
  std::string shape;
  for (std::size_t a = 0; a < info.shape.size(); ++a)
    shape.append(a ? " x " : "").append(std::to_string(info.shape[a]));
  o << "hpcplan scen: " << info.scenario << " on " << info.map << " (" << shape << ", "
    << info.connectivity << " connectivity), " << info.algorithm;
  if (info.algorithm == "wastar") o << " w=" << info.weight;
  o << ", " << info.engine << " engine, " << info.ranks << " rank(s)";
  if (info.ranks > 1) o << " (" << info.split << ")";
  o << "\n";
  std::snprintf(
      line, sizeof line, "  rows       %llu of %llu, %llu solved, %llu mismatches\n",
      static_cast<unsigned long long>(s.rows), static_cast<unsigned long long>(info.file_rows),
      static_cast<unsigned long long>(s.solved), static_cast<unsigned long long>(s.mismatches));
  o << line;
  if (!s.mismatch_rows.empty()) {
    o << "  mismatch   rows";
    for (std::size_t i = 0; i < s.mismatch_rows.size() && i < 20; ++i)
      o << " " << s.mismatch_rows[i];
    if (s.mismatch_rows.size() > 20) o << " ... (" << s.mismatch_rows.size() << " in all)";
    o << "\n";
  }
  std::snprintf(line, sizeof line,
                "  time       load %.1f ms; queries p50 %.1f us, p95 %.1f us, max %.1f us; "
                "%.3g states/s; wall %.1f ms\n",
                info.load_ms, s.p50_us, s.p95_us, s.max_us, s.states_per_second, info.wall_ms);
  o << line;
  // Buckets, at most 12 lines: the first, the last and evenly spaced ones between.
  const std::size_t n = s.buckets.size();
  const std::size_t shown = std::min<std::size_t>(n, 12);
  if (n > 0) o << "  bucket     rows      p50 us      p95 us      max us   mean expanded\n";
  for (std::size_t k = 0; k < shown; ++k) {
    const std::size_t i = shown == 1 ? 0 : k * (n - 1) / (shown - 1);
    const BucketTimes& b = s.buckets[i];
    std::snprintf(line, sizeof line, "  %6d %8llu %11.1f %11.1f %11.1f %15.0f\n", b.bucket,
                  static_cast<unsigned long long>(b.rows), b.p50_us, b.p95_us, b.max_us,
                  b.mean_expanded);
    o << line;
  }
  return o.str();
}

}  // namespace hpcplan
