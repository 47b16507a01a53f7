#include "hpcplan/io/rank_simulation_json.hpp"

#include <algorithm>
#include <cstdio>

namespace hpcplan {

nlohmann::json to_json(const partition::RankSimulation& sim) {
  nlohmann::json splits = nlohmann::json::array();
  for (const auto& s : sim.splits) {
    // Where the serial expansions split evenly (hpcplan grid --owner-cuts), for this P.
    nlohmann::json cuts = nlohmann::json::array();
    if (s.ranks <= static_cast<int>(sim.expanded_by_prefix.size()))
      cuts = partition::balanced_prefix_cuts(sim, s.ranks);
    std::uint64_t max_ex = 0, min_ex = ~0ULL;
    for (auto e : s.expanded) {
      max_ex = std::max(max_ex, e);
      min_ex = std::min(min_ex, e);
    }
    splits.push_back({{"ranks", s.ranks},
                      {"coarsen_shift", s.coarsen_shift},
                      {"expansion_deviation_percent", s.expansion_deviation_percent},
                      {"stored_deviation_percent", s.stored_deviation_percent},
                      {"imbalance", s.imbalance},
                      {"max_expanded_per_rank", max_ex},
                      {"min_expanded_per_rank", min_ex},
                      {"remote_successors", s.remote_successors},
                      {"remote_fraction", s.remote_fraction},
                      {"remote_per_expansion", s.remote_per_expansion},
                      {"balanced_prefix_cuts", cuts}});
  }
  return splits;
}

std::string to_summary(const partition::RankSimulation& sim) {
  std::string out =
      "  predicted split (serial search observed; ownership hash of the state, or of its cell "
      "for k > 0)\n"
      "     ranks   k  expand dev %  stored dev %  max/mean  max expanded/rank  remote succ. %  "
      "remote/expansion\n";
  char line[200];
  for (const auto& s : sim.splits) {
    std::uint64_t max_ex = 0;
    for (auto e : s.expanded) max_ex = std::max(max_ex, e);
    std::snprintf(line, sizeof line, "  %8d %3d %13.3f %13.3f %9.3f %18llu %15.2f %17.3f\n",
                  s.ranks, s.coarsen_shift, s.expansion_deviation_percent,
                  s.stored_deviation_percent, s.imbalance, static_cast<unsigned long long>(max_ex),
                  100.0 * s.remote_fraction, s.remote_per_expansion);
    out += line;
  }
  // The cuts depend on P only, so once per rank count, and only where they fit on a line.
  std::vector<int> shown;
  for (const auto& s : sim.splits) {
    if (s.ranks < 2 || s.ranks > 16 ||
        std::find(shown.begin(), shown.end(), s.ranks) != shown.end())
      continue;
    shown.push_back(s.ranks);
    if (s.ranks > static_cast<int>(sim.expanded_by_prefix.size())) continue;
    std::string list;
    for (auto c : partition::balanced_prefix_cuts(sim, s.ranks)) {
      if (!list.empty()) list += ',';
      list += std::to_string(c);
    }
    out += "  balanced --owner-cuts for " + std::to_string(s.ranks) + " ranks: " + list + "\n";
  }
  return out;
}

}  // namespace hpcplan
