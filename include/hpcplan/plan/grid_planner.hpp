#pragma once
// Solves a GridProblem with the serial engine and reports everything a user or a later
// analysis needs: the problem as actually solved (adjusted start/goal, threshold, density),
// the options, the result and its counters.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/search/search_result.hpp"

namespace hpcplan {

struct GridReport {
  // Problem as solved.
  int dims = 0;
  int extent = 0;
  std::uint64_t seed = 0;
  int threshold = 0;
  double blocked_fraction = 0.0;
  int shift_p = 0;
  int shift_v = 0;
  std::string connectivity;
  std::vector<int> start, goal;
  bool start_adjusted = false, goal_adjusted = false;
  int key_words = 1;
  // Options.
  std::string algorithm;
  double weight = 1.0;
  std::string heuristic;
  std::uint64_t max_states = 0;
  std::string visited_map;
  int ranks = 1;
  // Result.
  search::Status status = search::Status::no_path;
  double cost = 0.0;
  std::uint64_t hops = 0;
  double straight_line = 0.0;
  double quality = 0.0;  // cost / straight_line (seed 002 eq. 2)
  search::Counters counters;
  double setup_ms = 0.0;
  std::vector<std::vector<int>> path;
};

GridReport solve_grid(const GridProblem& problem, const GridSearchOptions& options);

}  // namespace hpcplan
