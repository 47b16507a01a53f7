#include "hpcplan/partition/rank_simulation.hpp"

#include <optional>
#include <absl/container/flat_hash_set.h>

#include <algorithm>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/partition/ownership.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"

namespace hpcplan::partition {

double deviation_percent(const std::vector<std::uint64_t>& counts) {
  if (counts.size() < 2) return 0.0;
  std::uint64_t total = 0;
  for (auto c : counts) total += c;
  if (total == 0) return 0.0;
  const auto [lo, hi] = std::minmax_element(counts.begin(), counts.end());
  return 100.0 * static_cast<double>(*hi - *lo) / static_cast<double>(total);
}

namespace {

// The lattice graph seen through every (P, k) ownership at once. Only observes: successors,
// costs and moves pass through unchanged, so the search is the serial one.
template <int W>
class OwnershipCensus {
 public:
  using State = PackedKey<W>;
  using Move = typename LatticeGraph<W>::Move;
  using Cost = typename LatticeGraph<W>::Cost;
  using Hash = typename LatticeGraph<W>::Hash;
  static constexpr Move kNoMove = LatticeGraph<W>::kNoMove;

  OwnershipCensus(const LatticeGraph<W>& graph, const std::vector<int>& shifts,
                  std::vector<SimulatedSplit>& splits, std::vector<std::uint64_t>& by_prefix)
      : graph_(graph),
        splits_(splits),
        by_prefix_(by_prefix),
        positions_(graph.layout(), 1, 0, 0, graph.field().extent()) {
    const std::uint64_t n = prefix_positions(graph.layout().dims(), graph.field().extent());
    if (n <= RankSimulation::kMaxCensusPositions) by_prefix_.assign(n, 0);
    for (int k : shifts) cells_.emplace_back(graph.layout(), 1, k);
    for (const auto& s : splits) {
      const auto it = std::find(shifts.begin(), shifts.end(), s.coarsen_shift);
      kind_.push_back(static_cast<int>(it - shifts.begin()));
    }
    hx_.resize(shifts.size());
    ox_.resize(splits.size());
    ht_.resize(shifts.size());
  }

  void observe_start(const State& s) {
    seen_.insert(s);
    hashes(s, ht_);
    for (std::size_t i = 0; i < splits_.size(); ++i) splits_[i].stored[owner(ht_, i)]++;
  }

  template <class Emit>
  void for_each_successor(const State& x, Emit&& emit) const {
    hashes(x, hx_);
    if (!by_prefix_.empty()) by_prefix_[positions_.position(x)]++;
    for (std::size_t i = 0; i < splits_.size(); ++i) {
      ox_[i] = owner(hx_, i);  // once per expansion, not per successor
      splits_[i].expanded[ox_[i]]++;
    }
    graph_.for_each_successor(x, [&](const State& t, const Cost& c, Move m) {
      hashes(t, ht_);
      const bool fresh = seen_.insert(t).second;
      for (std::size_t i = 0; i < splits_.size(); ++i) {
        SimulatedSplit& s = splits_[i];
        const int o = owner(ht_, i);
        s.generated++;
        if (o != ox_[i]) s.remote_successors++;
        if (fresh) s.stored[o]++;
      }
      emit(t, c, m);
    });
  }

  State predecessor(const State& s, Move m) const { return graph_.predecessor(s, m); }
  double checked_edge_length(const State& a, const State& b) const {
    return graph_.checked_edge_length(a, b);
  }
  std::uint64_t collision_checks() const { return graph_.collision_checks(); }

 private:
  void hashes(const State& s, std::vector<std::uint64_t>& out) const {
    for (std::size_t k = 0; k < cells_.size(); ++k) out[k] = hash_key(cells_[k].cell(s));
  }
  int owner(const std::vector<std::uint64_t>& h, std::size_t split) const {
    return static_cast<int>(h[kind_[split]] % static_cast<std::uint64_t>(splits_[split].ranks));
  }

  const LatticeGraph<W>& graph_;
  std::vector<SimulatedSplit>& splits_;
  std::vector<std::uint64_t>& by_prefix_;
  Ownership<W> positions_;           // one rank; used for position() only
  std::vector<Ownership<W>> cells_;  // one per shift, used for cell() only
  std::vector<int> kind_;            // split -> index into cells_
  mutable std::vector<std::uint64_t> hx_, ht_;
  mutable std::vector<int> ox_;  // the expanded state's owner, per split
  mutable absl::flat_hash_set<State, Hash> seen_;
};

template <int W>
void run(const ObstacleSource& field, const GridProblem& problem, const GridSearchOptions& o,
         const std::vector<int>& shifts, RankSimulation& sim) {
  GridReport& report = sim.serial;
  LatticeGraph<W> graph(field, problem.connectivity);
  OwnershipCensus<W> census(graph, shifts, sim.splits, sim.expanded_by_prefix);
  const auto start = graph.pack(report.problem.start);
  const auto goal = graph.pack(report.problem.goal);
  census.observe_start(start);
  const auto eo =
      hpcplan::detail::engine_options(o, report.options.weight, report.options.max_states);
  const auto r = hpcplan::detail::with_heuristic<W>(
      o, problem, graph.layout(), report.problem.goal, [&](const auto& h) {
        return search::best_first_search<search::DefaultVisitedMap>(census, start, goal, h, eo);
      });
  report.result.status = r.status;
  report.result.cost = r.cost;
  report.result.hops = r.hops;
  report.result.counters = r.counters;
}

}  // namespace

std::vector<std::uint32_t> balanced_prefix_cuts(const RankSimulation& sim, int ranks) {
  const auto& h = sim.expanded_by_prefix;
  const auto n = static_cast<std::uint32_t>(h.size());
  if (h.empty())
    throw InputError(
        "balanced prefix cuts: the lattice has more than " +
        std::to_string(RankSimulation::kMaxCensusPositions) +
        " positions (extent^2), too many to count expansions by position; give --owner-cuts "
        "or slabs by hand");
  if (ranks < 1 || static_cast<std::uint32_t>(ranks) > n)
    throw InputError("balanced prefix cuts: " + std::to_string(ranks) +
                     " ranks need as many prefix positions, the lattice has " + std::to_string(n));
  long double total = 0;
  for (auto c : h) total += static_cast<long double>(c);
  std::vector<std::uint32_t> cuts;
  long double running = 0;  // expansions at positions below p
  std::uint32_t p = 0;
  for (int j = 1; j < ranks; ++j) {
    const long double share = total * j / ranks;
    // Every rank keeps at least one position: cut j lies in lo..hi.
    const std::uint32_t lo = cuts.empty() ? 1 : cuts.back() + 1;
    const std::uint32_t hi = n - static_cast<std::uint32_t>(ranks - j);
    while (p < hi && (p < lo || running + static_cast<long double>(h[p]) / 2 < share))
      running += static_cast<long double>(h[p++]);
    // (The loop stops at the position whose midpoint first passes the share: the nearer of
    // the two cuts around it.)
    cuts.push_back(std::max(p, lo));
  }
  return cuts;
}

RankSimulation simulate_ranks(const GridProblem& problem, const GridSearchOptions& options,
                              const std::vector<int>& ranks, const std::vector<int>& shifts) {
  validate(problem, options);
  if (ranks.empty() || shifts.empty())
    throw InputError("--simulate-ranks needs at least one rank count and one ownership shift");
  for (int p : ranks)
    if (p < 1 || p > 65536)
      throw InputError("--simulate-ranks: rank counts must be in 1..65536, got " +
                       std::to_string(p));
  for (int k : shifts)
    if (k < 0 || k > 16)
      throw InputError("--simulate-coarsen: shifts must be in 0..16, got " + std::to_string(k));
  RankSimulation sim;
  for (int k : shifts)
    for (int p : ranks) {
      SimulatedSplit s;
      s.ranks = p;
      s.coarsen_shift = k;
      s.expanded.assign(p, 0);
      s.stored.assign(p, 0);
      sim.splits.push_back(std::move(s));
    }
  Stopwatch setup;
  std::optional<GogField> gog;
  const ObstacleSource field = obstacles_of(problem, gog);
  sim.serial = prepare_grid_report(problem, options, field, 1);
  sim.serial.result.setup_ms = setup.milliseconds();
  switch (sim.serial.options.key_words) {
    case 1:
      run<1>(field, problem, options, shifts, sim);
      break;
    case 2:
      run<2>(field, problem, options, shifts, sim);
      break;
    default:
      run<4>(field, problem, options, shifts, sim);
      break;
  }
  finish_grid_report(sim.serial);
  for (auto& s : sim.splits) {
    s.expansion_deviation_percent = deviation_percent(s.expanded);
    s.stored_deviation_percent = deviation_percent(s.stored);
    const std::uint64_t busiest = *std::max_element(s.expanded.begin(), s.expanded.end());
    const double mean = static_cast<double>(sim.serial.result.counters.expanded) / s.ranks;
    s.imbalance = mean > 0 ? static_cast<double>(busiest) / mean : 1.0;
    s.remote_fraction =
        s.generated ? static_cast<double>(s.remote_successors) / static_cast<double>(s.generated)
                    : 0.0;
    const std::uint64_t ex = std::max<std::uint64_t>(1, sim.serial.result.counters.expanded);
    s.remote_per_expansion = static_cast<double>(s.remote_successors) / static_cast<double>(ex);
  }
  return sim;
}

}  // namespace hpcplan::partition
