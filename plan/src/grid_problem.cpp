#include "hpcplan/plan/grid_problem.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/format.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/graph/packed_key.hpp"
#include "hpcplan/plan/planner_registry.hpp"

namespace hpcplan {

namespace {

// The GOG lattice's planners: the registry's "grid" entries and the enum they run as.
struct GridEntry {
  GridAlgorithm algorithm;
  plan::PlannerSpec spec;
};

const std::vector<GridEntry>& grid_entries() {
  static const std::vector<GridEntry> table = [] {
    const std::vector<std::string> worlds{"grid"};
    const std::vector<std::string> common{"heuristic", "connectivity", "max_states", "time_limit",
                                          "engine"};
    const std::vector<std::string> exhaustive{"connectivity", "max_states",      "time_limit",
                                              "engine",       "threads",         "memory_budget",
                                              "slab_layers",  "contiguous_slabs"};
    std::vector<std::string> weighted = common;
    weighted.insert(weighted.begin(), "weight");
    std::vector<std::string> with_jump_points = common;
    with_jump_points.push_back("no_jump_points");
    return std::vector<GridEntry>{
        {GridAlgorithm::astar,
         {"astar", "grid search", worlds, with_jump_points,
          "A* (f = g + h), optimal; at 2D on the lattice's jump points"}},
        {GridAlgorithm::wastar,
         {"wastar", "grid search", worlds, weighted,
          "weighted A* (f = g + w h), closed states not reopened, cost <= w x optimal"}},
        {GridAlgorithm::dijkstra,
         {"dijkstra", "grid search", worlds, exhaustive, "Dijkstra (h = 0), optimal"}},
        {GridAlgorithm::bfs,
         {"bfs", "grid search", worlds, exhaustive, "breadth-first search: fewest moves"}},
    };
  }();
  return table;
}

}  // namespace

namespace plan {
std::vector<PlannerSpec> grid_planner_specs() {
  std::vector<PlannerSpec> specs;
  for (const GridEntry& e : grid_entries()) specs.push_back(e.spec);
  return specs;
}
}  // namespace plan

GridAlgorithm parse_grid_algorithm(std::string_view name) {
  const plan::PlannerSpec& spec = plan::PlannerRegistry::get().require("grid", name);
  for (const GridEntry& e : grid_entries())
    if (e.spec.name == spec.name) return e.algorithm;
  throw std::logic_error("grid planner '" + spec.name + "' has no algorithm");
}

HeuristicKind parse_heuristic(std::string_view name) {
  if (name == "lattice") return HeuristicKind::lattice;
  if (name == "euclidean") return HeuristicKind::euclidean;
  throw InputError("unknown heuristic '" + std::string(name) + "' (expected lattice or euclidean)");
}

GridEngine parse_engine(std::string_view name) {
  if (name == "auto") return GridEngine::automatic;
  if (name == "dense") return GridEngine::dense;
  if (name == "sparse") return GridEngine::sparse;
  throw InputError("unknown engine '" + std::string(name) + "' (expected auto, dense or sparse)");
}

Connectivity parse_connectivity(std::string_view name) {
  if (name == "seed") return Connectivity::seed_pairs;
  if (name == "full") return Connectivity::full;
  throw InputError("unknown connectivity '" + std::string(name) + "' (expected seed or full)");
}

std::string_view to_string(GridAlgorithm a) {
  for (const GridEntry& e : grid_entries())
    if (e.algorithm == a) return e.spec.name;
  return "?";
}
std::string_view to_string(HeuristicKind h) {
  return h == HeuristicKind::lattice ? "lattice" : "euclidean";
}
std::string_view to_string(Connectivity c) {
  return c == Connectivity::seed_pairs ? "seed" : "full";
}

namespace {

void check_state(const std::optional<std::vector<int>>& s, const GridProblem& p,
                 std::string_view what) {
  if (!s) return;
  if (p.occupancy) {
    const std::vector<int>& shape = p.occupancy->shape();
    if (s->size() != shape.size())
      throw InputError(std::string(what) + " has " + std::to_string(s->size()) +
                       " coordinates but the map has " + std::to_string(shape.size()) +
                       " dimensions");
    for (std::size_t a = 0; a < shape.size(); ++a)
      if ((*s)[a] < 0 || (*s)[a] >= shape[a]) {
        std::string box;
        for (std::size_t b = 0; b < shape.size(); ++b)
          box += (b ? " x [0, " : "[0, ") + std::to_string(shape[b] - 1) + "]";
        throw InputError(std::string(what) + " (" + join_coordinates(*s) +
                         ") is outside the map " + box);
      }
    return;
  }
  if (static_cast<int>(s->size()) != p.dims)
    throw InputError(std::string(what) + " has " + std::to_string(s->size()) +
                     " coordinates but --dims is " + std::to_string(p.dims));
  for (int c : *s)
    if (c < 0 || c >= p.extent)
      throw InputError(std::string(what) + " (" + join_coordinates(*s) +
                       ") is outside the box [0, " + std::to_string(p.extent - 1) + "]");
}

}  // namespace

GridProblem occupancy_problem(std::shared_ptr<const OccupancyGrid> grid,
                              Connectivity connectivity) {
  GridProblem p;
  p.dims = grid->dims();
  p.extent = grid->extent();
  p.occupancy = std::move(grid);
  p.connectivity = connectivity;
  return p;
}

void validate(const GridProblem& p, const GridSearchOptions& o) {
  if (p.occupancy && (p.dims != p.occupancy->dims() || p.extent != p.occupancy->extent()))
    throw std::logic_error("GridProblem: dims and extent must be the occupancy grid's");
  if (p.dims < 1 || p.dims > kMaxDims)
    throw InputError("--dims must be in [1, 16], got " + std::to_string(p.dims));
  if (p.extent < 2 || p.extent > kMaxExtent)
    throw InputError("--extent must be in [2, 65535], got " + std::to_string(p.extent));
  if (p.connectivity == Connectivity::full && p.dims > kMaxFullConnectivityDims)
    throw InputError(p.occupancy ? "--connectivity full is limited to maps of at most 4 dimensions (3^d - 1 moves)" : "--connectivity full is limited to --dims <= 4 (3^d - 1 moves)");
  check_state(p.start, p, "--start");
  check_state(p.goal, p, "--goal");
  if (o.weight) {
    if (!std::isfinite(*o.weight) || *o.weight < 1.0)
      throw InputError("--weight must be a finite number >= 1");
    if (o.algorithm != GridAlgorithm::wastar && *o.weight != 1.0)
      throw InputError("--weight applies to --algo wastar only");
  }
  if (!(o.time_limit_s >= 0.0) || !std::isfinite(o.time_limit_s))
    throw InputError("--time-limit must be a non-negative number of seconds");
  if (o.engine == GridEngine::dense && o.algorithm != GridAlgorithm::bfs &&
      o.algorithm != GridAlgorithm::dijkstra)
    throw InputError(
        "--engine dense runs --algo bfs and dijkstra (A* and weighted A* run on the "
        "sparse engine)");
  // Here, where every rank validates before any communicates (a refusal inside the engine
  // could come from the serial reference on rank 0 alone, leaving the others at a barrier).
  if (o.engine == GridEngine::dense) dense::require_compiled(p.dims);
  if (o.slab_layers > 0 && o.contiguous_slabs)
    throw InputError("--slab-layers and --contiguous-slabs choose different layouts: give one");
  if (o.slab_layers < 0)
    throw InputError("--slab-layers must be 0 (automatic) or a number of layers");
  if (o.threads < 0 || o.threads > 4096)
    throw InputError("--threads must be in [0, 4096], got " + std::to_string(o.threads));
  if (!(o.checkpoint_every_s >= 0.0) || !std::isfinite(o.checkpoint_every_s))
    throw InputError("--checkpoint-every must be a non-negative number of seconds");
  if (o.checkpoint_every_s > 0.0 && o.checkpoint.empty())
    throw InputError("--checkpoint-every needs --checkpoint FILE");
  if ((!o.checkpoint.empty() || !o.restart.empty()) && o.algorithm != GridAlgorithm::bfs &&
      o.algorithm != GridAlgorithm::dijkstra)
    throw InputError(
        "--checkpoint and --restart need the dense engine: --algo bfs or dijkstra (A* and "
        "weighted A* end in seconds to minutes and are not checkpointed)");
}

void require_dense_for_checkpoints(const GridSearchOptions& o, int dims, bool dense) {
  if (dense || (o.checkpoint.empty() && o.restart.empty())) return;
  if (dims > dense::compiled_dims())
    throw InputError(
        "--checkpoint and --restart need the dense engine, which this build "
        "compiles for 1 to " +
        std::to_string(dense::compiled_dims()) + " dimensions (HPCPLAN_DENSE_DIMS), not " +
        std::to_string(dims));
  throw InputError(
      "--checkpoint and --restart need the dense engine, and this run would use the sparse "
      "one; give --engine dense (or a larger --memory-budget)");
}

std::vector<int> adjust_to_free(const ObstacleSource& field, std::vector<int> state, int direction,
                                std::string_view what) {
  const int d = field.dims();
  for (long step = 0; !field.is_free(state); ++step) {
    const int axis = static_cast<int>(step % d);
    state[axis] += direction;
    if (state[axis] < 0 || state[axis] >= field.size(axis))
      throw InputError("no free " + std::string(what) +
                       " found by advancing from the corner; choose it with --" +
                       std::string(what));
  }
  return state;
}

std::uint64_t bytes_per_state(int key_words) {
  const std::uint64_t key = 8ULL * static_cast<std::uint64_t>(key_words);
  const std::uint64_t slot = key + 16 + 1;  // key, node (g, move, flag), control byte
  const std::uint64_t frontier = 16 + key;  // heap entry (f, g, state)
  // A Swiss table runs between 7/16 and 7/8 full and briefly holds old and new arrays while
  // growing, so budget three slots per state.
  return 3 * slot + frontier;
}

}  // namespace hpcplan
