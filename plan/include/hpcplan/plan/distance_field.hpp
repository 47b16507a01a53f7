#pragma once
// The distance field of one start: every cell's distance from it on an occupancy grid (or a GOG
// field), by the dense engine (dense_search.hpp) run past the goal until the whole reachable
// set is settled. BFS gives each cell its hop count (level), Dijkstra its exact path cost; -1
// marks blocked and unreachable cells. `hpcplan grid --field-out FILE` writes it as a NumPy
// .npy of the grid's shape in NumPy order (the grid's axes reversed, C order: cells in grid
// order, axis 0 fastest), int32 for BFS, float32 for Dijkstra.
//
// Threads: the computation uses the dense engine's OpenMP threads; a DistanceField is a plain
// value.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hpcplan/dense/slab_transport.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan {

struct DistanceField {
  std::vector<int> shape;            // the grid's sides, axis 0 (x) first
  bool hops = false;                 // BFS: int32 levels; Dijkstra: float32 costs
  std::vector<std::int32_t> levels;  // BFS, one per cell in grid order (axis 0 fastest)
  std::vector<float> costs;          // Dijkstra, the same
  std::uint64_t reached = 0;         // cells with a value (>= 0)
  // The search ran to its end: false when a stop (time limit, budget, cancel) cut it short,
  // and then the field holds what was settled before it.
  bool complete = false;

  std::uint64_t cells() const;
  // The NumPy shape: the grid's sides reversed.
  std::vector<std::int64_t> numpy_shape() const;
  // The value of one cell (grid coordinates, axis 0 first): -1 when none.
  double at(std::span<const int> cell) const;
};

// A field run's answer: the grid report as for the same query with a goal (its goal the given
// one, or the start when none was given), and the field (whole on rank 0; empty elsewhere).
struct DistanceFieldRun {
  GridReport report;
  DistanceField field;
  bool goal_given = false;
};

// InputError (one line) unless the request can make a field: BFS or Dijkstra, not the sparse
// engine, no checkpoints.
void validate_distance_field(const GridProblem& problem, const GridSearchOptions& options);

// The problem a field run solves: the given one, its goal the start when none was given (the
// start's own default, adjusted, when that is not given either).
GridProblem distance_field_problem(const ObstacleSource& field, const GridProblem& problem);

// The OpenMP threads of a field run: those of any dense run on the field (grid_planner.hpp's
// dense_threads).
int distance_field_threads(const ObstacleSource& field, const GridSearchOptions& options,
                           int ranks_sharing_cpus);

// Serial (one process, the options' OpenMP threads).
DistanceFieldRun distance_field(const GridProblem& problem, const GridSearchOptions& options);
// On this process's slab, collective over the transport's ranks: every rank fills its slab's
// cells and rank 0 gathers them (SlabTransport::gather_to_root). `options` must already be
// agreed by every rank (threads and memory budget: solve_grid_distributed's agreement).
DistanceFieldRun distance_field(const ObstacleSource& field, const GridProblem& problem,
                                const GridSearchOptions& options, dense::SlabTransport& transport,
                                int ranks_sharing_memory);

// The .npy file's bytes, and the file written atomically (RunError if it cannot be).
std::string distance_field_npy(const DistanceField& field);
void write_distance_field(const std::string& path, const DistanceField& field);

}  // namespace hpcplan
