#include "hpcplan/io/grid_report_json.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "hpcplan/core/format.hpp"
#include "hpcplan/partition/ownership.hpp"

namespace hpcplan {
namespace {

nlohmann::json distributed_json(const GridReport& r) {
  nlohmann::json d;
  if (!r.prefix_cuts.empty())
    d["ownership"] = {
        {"prefix_cuts", {{"axes", partition::cut_axes(r.dims)}, {"at", r.prefix_cuts}}}};
  else if (r.slab_width > 0)
    d["ownership"] = {{"slabs", {{"axis", partition::slab_axis(r.dims)}, {"width", r.slab_width}}}};
  else
    d["ownership"] = {{"hash", "splitmix64"}, {"coarsen_shift", r.coarsen_shift}};
  d["batch"] = r.batch;
  d["batch_age_ms"] = r.batch_age_ms;
  d["sync_every"] = r.sync_every;
  d["workload_deviation_percent"] = workload_deviation_percent(r.per_rank);
  std::uint64_t messages = 0, bytes = 0, records = 0;
  double wait = 0.0;
  nlohmann::json ranks = nlohmann::json::array();
  for (std::size_t i = 0; i < r.per_rank.size(); ++i) {
    const auto& k = r.per_rank[i];
    messages += k.messages_sent;
    bytes += k.bytes_sent;
    records += k.records_sent;
    wait += k.wait_ms;
    ranks.push_back({{"rank", i},
                     {"expanded", k.expanded},
                     {"generated", k.generated},
                     {"collision_checks", k.collision_checks},
                     {"states_stored", k.states_stored},
                     {"peak_open", k.peak_open},
                     {"reopened", k.reopened},
                     {"messages_sent", k.messages_sent},
                     {"messages_received", k.messages_received},
                     {"bytes_sent", k.bytes_sent},
                     {"bytes_received", k.bytes_received},
                     {"records_sent", k.records_sent},
                     {"records_received", k.records_received},
                     {"records_filtered", k.records_filtered},
                     {"sync_rounds", k.sync_rounds},
                     {"wait_ms", k.wait_ms},
                     {"search_ms", k.search_ms}});
  }
  const double expanded = static_cast<double>(std::max<std::uint64_t>(1, r.counters.expanded));
  d["messages_sent"] = messages;
  d["bytes_sent"] = bytes;
  d["records_sent"] = records;
  d["messages_per_expansion"] = static_cast<double>(messages) / expanded;
  d["bytes_per_expansion"] = static_cast<double>(bytes) / expanded;
  d["wait_ms_total"] = wait;
  d["per_rank"] = ranks;
  return d;
}

}  // namespace

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
  j["pruning"] = r.pruning;
  j["scheme"] = r.scheme;
  if (r.scheme != "serial") j["distributed"] = distributed_json(r);
  if (r.has_serial_reference) {
    nlohmann::json s;
    const bool ok = r.serial_status == search::Status::solved;
    s["status"] = std::string(search::to_string(r.serial_status));
    s["cost"] = ok ? nlohmann::json(r.serial_cost) : nlohmann::json(nullptr);
    s["hops"] = ok ? nlohmann::json(r.serial_hops) : nlohmann::json(nullptr);
    s["expanded"] = r.serial_expanded;
    s["time_ms"] = r.serial_time_ms;
    // Search overhead: how many more states the ranks together expanded than one process.
    s["search_overhead"] = r.serial_expanded
                               ? nlohmann::json(static_cast<double>(r.counters.expanded) /
                                                static_cast<double>(r.serial_expanded))
                               : nlohmann::json(nullptr);
    s["speedup"] = r.counters.time_ms > 0 ? nlohmann::json(r.serial_time_ms / r.counters.time_ms)
                                          : nlohmann::json(nullptr);
    j["serial_reference"] = s;
  }
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
  if (r.pruning != "none") o << "  pruning    " << r.pruning << " (counts are of jump points)\n";
  std::snprintf(line, sizeof line, "  time       %.3f ms search, %.3f ms set-up\n",
                r.counters.time_ms, r.setup_ms);
  o << line;
  if (r.scheme != "serial") {
    std::uint64_t messages = 0, bytes = 0;
    for (const auto& k : r.per_rank) {
      messages += k.messages_sent;
      bytes += k.bytes_sent;
    }
    char owner[48];
    if (!r.prefix_cuts.empty())
      std::snprintf(owner, sizeof owner, "owner prefix cuts (%zu)", r.prefix_cuts.size());
    else if (r.slab_width > 0)
      std::snprintf(owner, sizeof owner, "owner slabs of %d", r.slab_width);
    else
      std::snprintf(owner, sizeof owner, "owner coarsen %d", r.coarsen_shift);
    std::snprintf(line, sizeof line,
                  "  ranks      %d (%s, %s): workload deviation %.2f%%, %llu "
                  "messages, %.1f MB sent\n",
                  r.ranks, r.scheme.c_str(), owner, workload_deviation_percent(r.per_rank),
                  static_cast<unsigned long long>(messages), bytes / 1e6);
    o << line;
  }
  if (r.has_serial_reference) {
    std::snprintf(line, sizeof line,
                  "  serial     %s, cost %.4f, %llu expanded, %.3f ms (speedup %.2fx)\n",
                  std::string(search::to_string(r.serial_status)).c_str(), r.serial_cost,
                  static_cast<unsigned long long>(r.serial_expanded), r.serial_time_ms,
                  r.counters.time_ms > 0 ? r.serial_time_ms / r.counters.time_ms : 0.0);
    o << line;
  }
  if (!r.path.empty()) {
    o << "  path      ";
    for (const auto& s : r.path) o << " " << coords(s);
    o << "\n";
  }
  return o.str();
}

}  // namespace hpcplan
