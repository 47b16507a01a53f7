#pragma once
// The grid planner on a configuration space (GridProblem::cspace): the lattice of
// graph/cspace_graph.hpp searched by the sparse engine (A*, weighted A*, Dijkstra, BFS) here,
// or by the distributed engine (distributed/grid_planner_mpi.hpp), with one report either way.
//
// Off-lattice ends: the start joins the nearest vertex whose straight motion from it is valid
// (the vertices of its cell, nearest first), the goal likewise; both motions are checked at
// the space's resolution and their lengths are part of the cost. Every returned path (start,
// the lattice's vertices, goal) is re-checked motion by motion with the space's one-state test,
// and its length must agree with the search's cost.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hpcplan/graph/cspace_graph.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/search/search_result.hpp"

namespace hpcplan {

// How many vertices around an end are tried: its cell's corners, nearest first.
inline constexpr std::size_t kCSpaceEndCandidates = 256;

// InputError for what a user could have got wrong: no space, start or goal of the wrong size,
// outside the bounds or in collision, cells out of range, the dense engine, checkpoints.
void validate_cspace(const GridProblem& problem, const GridSearchOptions& options);

// The serial planner.
GridReport solve_cspace(const GridProblem& problem, const GridSearchOptions& options);

// The steps every engine shares. begin: validates, fills the report's problem and options and
// the state budget (split among `ranks_sharing_memory`), and joins both ends to the lattice
// (false: nothing to search: one end joined nothing, the report says which and its status is
// no_path; or start and goal are one state, the report solved at cost 0).
struct CSpaceRun {
  GridReport report;
  CSpaceGraph::State start, goal;
  bool keep_path = false;  // the report keeps the path (it is re-checked either way)
};
bool begin_cspace_run(const GridProblem& problem, const GridSearchOptions& options,
                      const CSpaceGraph& graph, int ranks_sharing_memory, CSpaceRun& run);
// finish: the search's result (lattice path of the ranks' engine) made the report's: the ends'
// motions added, the whole path re-checked (InputError-free: a failed re-check is a RunError,
// an internal fault), quality derived.
void finish_cspace_run(const search::Result<CSpaceGraph::State>& result, const CSpaceGraph& graph,
                       CSpaceRun& run);

}  // namespace hpcplan
