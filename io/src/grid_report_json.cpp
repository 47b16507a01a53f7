#include "hpcplan/io/grid_report_json.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "hpcplan/core/format.hpp"
#include "hpcplan/partition/ownership.hpp"

namespace hpcplan {
namespace {

nlohmann::json distributed_json(const GridReport& report) {
  const GridDistribution& r = report.distribution;
  const int dims = report.problem.dims;
  nlohmann::json d;
  if (report.dense)
    d["ownership"] = {{"dense_slabs",
                       {{"axis", report.dense->cut_axis},
                        {"block_sections", report.dense->block_sections},
                        {"blocks", report.dense->blocks},
                        {"rank_sections", report.dense->rank_sections},
                        {"rank_peers", report.dense->rank_peers}}}};
  else if (!r.prefix_cuts.empty())
    d["ownership"] = {
        {"prefix_cuts", {{"axes", partition::cut_axes(dims)}, {"at", r.prefix_cuts}}}};
  else if (r.slab_width > 0)
    d["ownership"] = {{"slabs", {{"axis", partition::slab_axis(dims)}, {"width", r.slab_width}}}};
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
  const double expanded =
      static_cast<double>(std::max<std::uint64_t>(1, report.result.counters.expanded));
  if (report.dense) {
    // The dense engine's halo exchanges: all of its messages.
    messages = report.dense->halo_messages;
    bytes = report.dense->halo_bytes;
    wait = report.dense->exchange_ms;
  }
  d["messages_sent"] = messages;
  d["bytes_sent"] = bytes;
  d["records_sent"] = records;
  d["messages_per_expansion"] = static_cast<double>(messages) / expanded;
  d["bytes_per_expansion"] = static_cast<double>(bytes) / expanded;
  d["wait_ms_total"] = wait;
  d["per_rank"] = ranks;
  return d;
}

nlohmann::json dense_json(const dense::Figures& f) {
  nlohmann::json d;
  d["tile"] = f.in_tile_axes == 2 ? std::vector<int>{8, 8} : std::vector<int>{64};
  d["tiles"] = f.tiles;
  d["free_states"] = f.free_states;
  d["reached"] = f.reached;
  d["bytes_per_rank"] = f.bytes_per_rank;
  d["bytes_total"] = f.bytes_total;
  d["levels"] = f.levels;
  d["buckets"] = f.buckets;
  d["active_tiles"] = f.active_tiles;
  d["step_active_tiles"] = f.step_active_tiles;
  d["threads"] = f.threads;
  d["cut_axis"] = f.cut_axis;
  d["block_sections"] = f.block_sections;
  d["blocks"] = f.blocks;
  d["rank_sections"] = f.rank_sections;
  d["rank_peers"] = f.rank_peers;
  d["halo_messages"] = f.halo_messages;
  d["halo_bytes"] = f.halo_bytes;
  d["exchange_ms"] = f.exchange_ms;
  d["rank_expanded"] = f.rank_expanded;
  d["rank_search_ms"] = f.rank_search_ms;
  return d;
}

}  // namespace

nlohmann::json to_json(const GridReport& report, bool include_path) {
  const GridProblemReport& p = report.problem;
  const GridOptionsReport& o = report.options;
  const GridResult& r = report.result;
  nlohmann::json j;
  j["status"] = std::string(search::to_string(r.status));
  if (!report.interrupted_by.empty()) j["interrupted_by"] = report.interrupted_by;
  if (!report.checkpoint.empty()) j["checkpoint"] = report.checkpoint;
  if (!report.restarted_from.empty()) j["restarted_from"] = report.restarted_from;
  j["dims"] = p.dims;
  j["algo"] = o.algorithm;
  j["weight"] = o.weight;
  j["heuristic"] = o.heuristic;
  j["connectivity"] = p.connectivity;
  j["obstacles"] = p.obstacles;
  j["extent"] = p.extent;
  if (report.cspace) {
    const CSpaceReport& c = *report.cspace;
    nlohmann::json cs;
    cs["world"] = c.world;
    cs["cells"] = c.cells;
    cs["moves"] = c.moves;
    cs["resolution"] = c.resolution;
    cs["periodic"] = c.periodic;
    cs["start"] = c.start;
    cs["goal"] = c.goal;
    cs["start_vertex"] = c.start_vertex;
    cs["goal_vertex"] = c.goal_vertex;
    cs["start_connection"] = c.start_connection;
    cs["goal_connection"] = c.goal_connection;
    if (!c.unconnected.empty()) cs["unconnected"] = c.unconnected;
    cs["path_rechecked"] = c.path_rechecked;
    cs["check_batches"] = c.batches;
    cs["metric"] = "euclidean (periodic axes the short way)";
    j["cspace"] = cs;
    j["world"] = c.world;
  }
  if (p.obstacles == "gog") {
    j["seed"] = p.seed;
    j["threshold"] = p.threshold;
    j["gog_shift_p"] = p.shift_p;
    j["gog_shift_v"] = p.shift_v;
  } else if (p.obstacles != "cspace") {
    j["map"] = p.map;
    j["shape"] = p.shape;  // x first
    j["map_checksum"] = p.map_checksum;
  }
  j["blocked_fraction"] = p.blocked_fraction;
  j["start"] = p.start;
  j["goal"] = p.goal;
  j["start_adjusted"] = p.start_adjusted;
  j["goal_adjusted"] = p.goal_adjusted;
  const bool solved = r.status == search::Status::solved;
  // Unsolved runs have no cost: null rather than a misleading 0.
  j["cost"] = solved ? nlohmann::json(r.cost) : nlohmann::json(nullptr);
  j["hops"] = solved ? nlohmann::json(r.hops) : nlohmann::json(nullptr);
  j["quality"] = solved ? nlohmann::json(r.quality) : nlohmann::json(nullptr);
  j["straight_line"] = p.straight_line;
  j["expanded"] = r.counters.expanded;
  j["generated"] = r.counters.generated;
  j["reopened"] = r.counters.reopened;
  j["collision_checks"] = r.counters.collision_checks;
  j["peak_states"] = r.counters.peak_states;
  j["peak_open"] = r.counters.peak_open;
  j["max_states"] = o.max_states;
  j["time_ms"] = r.counters.time_ms;
  j["setup_ms"] = r.setup_ms;
  j["ranks"] = report.distribution.ranks;
  j["key_words"] = o.key_words;
  j["visited_map"] = o.visited_map;
  j["pruning"] = o.pruning;
  j["engine"] = o.engine;
  if (report.dense) j["dense"] = dense_json(*report.dense);
  j["scheme"] = report.distribution.scheme;
  if (report.distribution.scheme != "serial") j["distributed"] = distributed_json(report);
  if (report.serial) {
    const SerialReference& sr = *report.serial;
    nlohmann::json s;
    const bool ok = sr.status == search::Status::solved;
    s["status"] = std::string(search::to_string(sr.status));
    s["cost"] = ok ? nlohmann::json(sr.cost) : nlohmann::json(nullptr);
    s["hops"] = ok ? nlohmann::json(sr.hops) : nlohmann::json(nullptr);
    s["expanded"] = sr.expanded;
    s["time_ms"] = sr.time_ms;
    // Search overhead: how many more states the ranks together expanded than one process.
    s["search_overhead"] = sr.expanded ? nlohmann::json(static_cast<double>(r.counters.expanded) /
                                                        static_cast<double>(sr.expanded))
                                       : nlohmann::json(nullptr);
    s["speedup"] = r.counters.time_ms > 0 ? nlohmann::json(sr.time_ms / r.counters.time_ms)
                                          : nlohmann::json(nullptr);
    j["serial_reference"] = s;
  }
  if (include_path) {
    j["path"] = r.path;
    // On a configuration space, the path in its own coordinates too (start, vertices, goal).
    if (report.cspace) j["path_states"] = report.cspace->path;
  }
  return j;
}

std::string to_summary(const GridReport& report) {
  const GridProblemReport& p = report.problem;
  const GridOptionsReport& op = report.options;
  const GridDistribution& d = report.distribution;
  const GridResult& r = report.result;
  auto coords = [](const std::vector<int>& s) {
    return std::string("(").append(join_coordinates(s)).append(")");
  };
  std::ostringstream o;
  char line[256];
  if (report.cspace) {
    const CSpaceReport& c = *report.cspace;
    o << "hpcplan grid: " << op.algorithm << " on " << c.world << " (" << p.dims << " axes), "
      << c.cells << " cells per axis, " << d.ranks << " rank(s)\n";
    std::snprintf(line, sizeof line,
                  "  lattice    %s moves, motions checked every %.4g, %llu batches of checks\n",
                  c.moves.c_str(), c.resolution, static_cast<unsigned long long>(c.batches));
  } else if (p.obstacles == "gog") {
    o << "hpcplan grid: " << op.algorithm << " in " << p.dims << "D, extent " << p.extent
      << ", seed " << p.seed << ", " << d.ranks << " rank(s)\n";
    std::snprintf(line, sizeof line, "  field      threshold %d, %.1f%% of states blocked\n",
                  p.threshold, 100.0 * p.blocked_fraction);
  } else {
    std::string shape;
    for (std::size_t a = 0; a < p.shape.size(); ++a)
      shape += (a ? " x " : "") + std::to_string(p.shape[a]);
    o << "hpcplan grid: " << op.algorithm << " in " << p.dims << "D on " << p.map << " ("
      << p.obstacles << ", " << shape << "), " << d.ranks << " rank(s)\n";
    std::snprintf(line, sizeof line, "  map        %s connectivity, %.1f%% of cells blocked\n",
                  p.connectivity.c_str(), 100.0 * p.blocked_fraction);
  }
  o << line;
  if (report.cspace) {
    const CSpaceReport& c = *report.cspace;
    auto reals = [](const std::vector<double>& q) {
      std::string s = "(";
      char v[32];
      for (std::size_t i = 0; i < q.size(); ++i) {
        std::snprintf(v, sizeof v, "%s%.4g", i ? "," : "", q[i]);
        s += v;
      }
      return s + ")";
    };
    o << "  start      " << reals(c.start) << ", joins vertex " << coords(p.start) << "\n";
    o << "  goal       " << reals(c.goal) << ", joins vertex " << coords(p.goal) << "\n";
    if (!c.unconnected.empty())
      o << "  note       the " << c.unconnected
        << " joins no lattice vertex next to it by a valid motion (try more --cells)\n";
  } else {
    o << "  start      " << coords(p.start) << (p.start_adjusted ? " (adjusted)" : "") << "\n";
    o << "  goal       " << coords(p.goal) << (p.goal_adjusted ? " (adjusted)" : "") << "\n";
  }
  o << "  status     " << search::to_string(r.status);
  if (!report.interrupted_by.empty())
    o << " by " << report.interrupted_by << "; continue with --restart " << report.checkpoint;
  o << "\n";
  if (!report.restarted_from.empty()) o << "  restarted  from " << report.restarted_from << "\n";
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
  if (op.pruning != "none") o << "  pruning    " << op.pruning << " (counts are of jump points)\n";
  if (report.dense) {
    const dense::Figures& f = *report.dense;
    std::snprintf(line, sizeof line,
                  "  dense      %s tiles, %llu %s, %d thread(s), %s per rank, %.4g of %.4g free "
                  "states reached\n",
                  f.in_tile_axes == 2 ? "8x8" : "64x1", static_cast<unsigned long long>(f.levels),
                  op.algorithm == "bfs" ? "levels" : "cost classes", f.threads,
                  format_bytes(f.bytes_per_rank).c_str(), static_cast<double>(f.reached),
                  static_cast<double>(f.free_states));
    o << line;
    std::snprintf(
        line, sizeof line,
        "  active     %llu tile visits of %llu tiles (%.3g per state reached), %d "
        "rank(s) x %d thread(s)\n",
        static_cast<unsigned long long>(f.active_tiles), static_cast<unsigned long long>(f.tiles),
        f.reached ? static_cast<double>(f.active_tiles) / f.reached : 0.0, f.ranks, f.threads);
    o << line;
  }
  std::snprintf(line, sizeof line, "  time       %.3f ms search, %.3f ms set-up\n",
                r.counters.time_ms, r.setup_ms);
  o << line;
  if (d.scheme != "serial") {
    std::uint64_t messages = 0, bytes = 0;
    for (const auto& k : d.per_rank) {
      messages += k.messages_sent;
      bytes += k.bytes_sent;
    }
    char owner[48];
    if (report.dense) {
      messages = report.dense->halo_messages;
      bytes = report.dense->halo_bytes;
      std::snprintf(owner, sizeof owner, "slabs of the last axis");
    } else if (!d.prefix_cuts.empty())
      std::snprintf(owner, sizeof owner, "owner prefix cuts (%zu)", d.prefix_cuts.size());
    else if (d.slab_width > 0)
      std::snprintf(owner, sizeof owner, "owner slabs of %d", d.slab_width);
    else
      std::snprintf(owner, sizeof owner, "owner coarsen %d", d.coarsen_shift);
    std::snprintf(line, sizeof line,
                  "  ranks      %d (%s, %s): workload deviation %.2f%%, %llu "
                  "messages, %.1f MB sent\n",
                  d.ranks, d.scheme.c_str(), owner, workload_deviation_percent(d.per_rank),
                  static_cast<unsigned long long>(messages), bytes / 1e6);
    o << line;
  }
  if (report.serial) {
    const SerialReference& sr = *report.serial;
    std::snprintf(line, sizeof line,
                  "  serial     %s, cost %.4f, %llu expanded, %.3f ms (speedup %.2fx)\n",
                  std::string(search::to_string(sr.status)).c_str(), sr.cost,
                  static_cast<unsigned long long>(sr.expanded), sr.time_ms,
                  r.counters.time_ms > 0 ? sr.time_ms / r.counters.time_ms : 0.0);
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
