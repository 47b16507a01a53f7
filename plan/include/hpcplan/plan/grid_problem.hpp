#pragma once
// A grid planning request, validated as a whole: what the CLI, benchmarks and the distributed
// layer all build before searching. It plans on the GOG field it describes, or on an occupancy
// grid a user brought (a map file, an array).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/obstacle_source.hpp"
#include "hpcplan/env/config_space.hpp"
#include "hpcplan/graph/cspace_graph.hpp"
#include "hpcplan/graph/lattice_graph.hpp"

namespace hpcplan {

enum class GridAlgorithm { astar, wastar, dijkstra, bfs };
enum class HeuristicKind { lattice, euclidean };
// Which engine searches: the dense bit-parallel one (BFS and Dijkstra over the whole lattice),
// the sparse best-first one, or the dense one where it applies and fits the memory budget.
enum class GridEngine { automatic, dense, sparse };

GridAlgorithm parse_grid_algorithm(std::string_view name);  // InputError if unknown
HeuristicKind parse_heuristic(std::string_view name);
Connectivity parse_connectivity(std::string_view name);
GridEngine parse_engine(std::string_view name);
std::string_view to_string(GridAlgorithm a);
std::string_view to_string(HeuristicKind h);
std::string_view to_string(Connectivity c);

// "3,4,5" -> {3,4,5}; InputError naming `what` on anything malformed.
std::vector<int> parse_coordinates(std::string_view text, std::string_view what);

// A query on a configuration space (env/config_space.hpp): the space, the lattice's moves, and
// start and goal in the space's own coordinates (off the lattice: each joins it by a checked
// motion to a nearby vertex).
struct CSpaceQuery {
  std::shared_ptr<const ConfigSpace> space;
  CSpaceMoves moves = CSpaceMoves::seed_pairs;
  std::vector<double> start, goal;
  bool batch_checks = true;  // false: one state at a time (the baseline; same answers)
};

struct GridProblem {
  int dims = 2;
  int extent = 100;
  GogParams gog;
  // Set: the problem plans on this grid, not on GOG (dims and extent must be the grid's;
  // occupancy_problem() sets them). Shared, so many queries on one map hold one copy.
  std::shared_ptr<const OccupancyGrid> occupancy;
  Connectivity connectivity = Connectivity::seed_pairs;
  // Set: the problem plans on this configuration space's lattice (plan/cspace_planner.hpp),
  // `extent` cells per axis, dims the space's; start and goal are then cspace->start/goal.
  std::optional<CSpaceQuery> cspace;
  std::optional<std::vector<int>> start;  // default: (0,...,0), adjusted until free
  std::optional<std::vector<int>> goal;   // default: (extent-1,...), adjusted until free
};

struct GridSearchOptions {
  GridAlgorithm algorithm = GridAlgorithm::astar;
  std::optional<double> weight;  // weighted A* only; default 2
  HeuristicKind heuristic = HeuristicKind::lattice;
  std::uint64_t max_states = 0;  // 0 = derived from available memory
  double time_limit_s = 0.0;     // 0 = none; counted from the start of the search
  std::stop_token cancel;        // another thread may end the search (status cancelled)
  // Also ends it (status cancelled) once true; evaluated on the search's thread every 64th
  // expansion (OMPL's termination condition).
  std::function<bool()> stop_when;
  bool keep_path = false;
  // 2D A* (weight 1) searches the lattice's jump points (graph/jump_point_graph.hpp): the same
  // optimal cost, far fewer expansions. False: every lattice state, as at other d.
  bool jump_points = true;
  GridEngine engine = GridEngine::automatic;
  // The dense engine's OpenMP threads (0: this process's share of the cores) and memory budget
  // in bytes (0: what max_states buys the sparse engine, max_states x bytes_per_state).
  int threads = 0;
  std::uint64_t memory_budget = 0;
  // Its layout over ranks and threads: blocks of this many layers dealt round (0: about 8 per
  // thread), or one contiguous slab per rank and thread balanced by free states.
  int slab_layers = 0;
  bool contiguous_slabs = false;
  // The dense engine's checkpoints (dense/dense_checkpoint.hpp says what is saved): written to
  // `checkpoint` (one file per rank, FILE.r<rank> on several) every `checkpoint_every_s`
  // seconds (0: only when interrupted) and when `interrupted` turns true (the run then ends
  // with status interrupted); `restart` continues from such files. BFS and Dijkstra only.
  std::string checkpoint, restart;
  double checkpoint_every_s = 0.0;
  std::function<bool()> interrupted;
};

// A problem on an occupancy grid, its dims and extent the grid's.
GridProblem occupancy_problem(std::shared_ptr<const OccupancyGrid> grid,
                              Connectivity connectivity = Connectivity::seed_pairs);

// Throws InputError for anything a user could have got wrong.
void validate(const GridProblem& problem, const GridSearchOptions& options);
// InputError if the options ask for checkpoints and the run does not use the dense engine.
void require_dense_for_checkpoints(const GridSearchOptions& options, int dims, bool dense);

// Seed 002 III-B: from the nominal corner, advance one voxel at a time, one axis after another
// (axis 0, 1, ..., d-1, 0, ...), towards the opposite corner until the state is free.
// Returns the free state; InputError if the walk leaves the box first.
std::vector<int> adjust_to_free(const ObstacleSource& field, std::vector<int> state, int direction,
                                std::string_view what);

// Bytes one stored state costs the search (visited-map slot at typical load, frontier entry).
std::uint64_t bytes_per_state(int key_words);

}  // namespace hpcplan
