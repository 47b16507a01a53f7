#pragma once
// Predicts how a distributed run would split the work, for rank counts this machine cannot
// run: the serial engine searches once, in one process, through a graph adaptor that asks, for
// every expansion and every generated successor, which rank would own it under P ranks and
// ownership shift k (partition::Ownership, the hash the real runs use). Reported per (P, k):
// expansions and stored states per rank (workload deviation, seed 002 Table IV) and the
// successors that would cross ranks (records before the sent-duplicate filter).
//
// The prediction is exact for the serial expansion order; a real run's order differs a little
// (search overhead <= 1.01 for Dijkstra and bulk-synchronous A*, tests/mpi compares the two at
// P = 2, 4, 8). It says nothing about time: message latency and waiting are not modelled.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::partition {

struct SimulatedSplit {
  int ranks = 1;
  int coarsen_shift = 0;
  std::vector<std::uint64_t> expanded;  // per rank
  std::vector<std::uint64_t> stored;    // per rank: distinct states reached
  std::uint64_t generated = 0;
  std::uint64_t remote_successors = 0;       // generated on one rank, owned by another
  double expansion_deviation_percent = 0.0;  // max - min share of expansions
  double stored_deviation_percent = 0.0;
  double imbalance = 1.0;        // busiest rank's expansions / the mean: the slowdown
                                 // against perfect balance, whatever P
  double remote_fraction = 0.0;  // remote / generated
  double remote_per_expansion = 0.0;
};

struct RankSimulation {
  GridReport serial;  // the search that was observed
  std::vector<SimulatedSplit> splits;
  // The serial expansions by prefix position (Ownership::position, a * extent + b on the cut
  // axes): the work model that balanced_prefix_cuts splits. Empty for lattices of more than
  // kMaxCensusPositions positions (extent > 2048 from 2D up), whose table would not fit.
  std::vector<std::uint64_t> expanded_by_prefix;
  static constexpr std::uint64_t kMaxCensusPositions = std::uint64_t{1} << 22;
};

// InputError for rank counts outside 1..65536 or shifts outside 0..16.
RankSimulation simulate_ranks(const GridProblem& problem, const GridSearchOptions& options,
                              const std::vector<int>& ranks, const std::vector<int>& shifts);

// The P - 1 prefix positions that split the observed expansions most evenly over P ranks,
// each cut where the running total first reaches its share (j/P of the whole). Positions
// ascend strictly, so a prefix heavier than a share still leaves every rank some states.
// InputError when P exceeds the prefix positions, or when the census has none (too large).
std::vector<std::uint32_t> balanced_prefix_cuts(const RankSimulation& sim, int ranks);

// Max - min of the shares (in percent) of `counts`; 0 for one rank.
double deviation_percent(const std::vector<std::uint64_t>& counts);

}  // namespace hpcplan::partition
