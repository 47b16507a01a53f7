#include "hpcplan/io/rank_simulation_json.hpp"

#include <algorithm>
#include <cstdio>

namespace hpcplan {

nlohmann::json to_json(const partition::RankSimulation& sim) {
  nlohmann::json splits = nlohmann::json::array();
  for (const auto& s : sim.splits) {
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
                      {"remote_per_expansion", s.remote_per_expansion}});
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
  return out;
}

}  // namespace hpcplan
