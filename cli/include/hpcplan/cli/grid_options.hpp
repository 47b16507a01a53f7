#pragma once
// hpcplan grid's options that every front end shares (the executable; the Python module's
// hpcplan.grid.solve): registered on a CLI11 command, read into the problem and the search's
// options with the checks that go with them, and the report's finishing touches. The
// executable adds its distributed and prediction options and --json (src/grid_command.cpp).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hpcplan/cli/run_control.hpp"
#include "hpcplan/plan/distance_field.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::cli {

struct GridArgs {
  GridProblem problem;
  GridSearchOptions options;
  std::string algo = "astar";
  std::string heuristic = "lattice";
  std::string connectivity = "seed";
  std::string engine = "auto";
  std::string start, goal, output;
  // --field-out FILE: the distance field of --start (.npy) instead of one query's path.
  std::string field_out;
  // --map FILE: plan on the occupancy grid of a .map, .3dmap or .npy instead of GOG.
  std::string map;
  // --world chain|hypercube: plan on that configuration space's lattice (--cells per axis,
  // --moves, --resolution); --start/--goal are then states in the space's coordinates.
  std::string world;
  int cells = 0;  // 0: the space's default
  std::string moves = "pairs";
  std::string checks = "batch";  // batch | single (one state at a time)
  double resolution = 0.0;  // 0: the space's default fraction of its extent
  // Set by a front end that defines its own space (Python's valid=fn): planned on like a
  // --world, with --cells, --start and --goal required.
  std::shared_ptr<const ConfigSpace> space;
  double weight = 2.0;
  bool no_jump_points = false;
  const CLI::Option* weight_option = nullptr;  // given or not (only weighted A* takes one)
  const CLI::Option* dims_option = nullptr;
  const CLI::Option* connectivity_option = nullptr;
  std::vector<const CLI::Option*> gog_options;  // GOG's own (refused with --map)
};

// The occupancy grid of a map file for a run starting at `start` (a .map's water class when the
// start stands in water), with the connectivity its published answers assume (seed or full;
// a .npy's is the caller's `fallback`).
struct LoadedMap {
  std::shared_ptr<const OccupancyGrid> grid;
  Connectivity connectivity = Connectivity::seed_pairs;
};
LoadedMap load_map(const std::string& path, const std::optional<std::vector<int>>& start,
                   Connectivity fallback);

// Registers the problem, search, checkpoint and output options on `command`.
void add_grid_options(CLI::App* command, GridArgs& args);

// --field-out (the executable's: the Python module does not take it): the whole map's distances
// from --start as a NumPy .npy (plan/distance_field.hpp).
void add_field_option(CLI::App* command, GridArgs& args);
// After prepare_grid_run, with --field-out given: InputError (one line, before any search) for
// what cannot make a field (A*, weighted A*, --engine sparse, checkpoints) and for a file that
// cannot be written.
void check_field_request(const GridArgs& args);
// The report's part about the field: where it went, its shape, dtype and reached cells.
nlohmann::json field_json(const DistanceField& field, const std::string& path, bool written,
                          bool goal_given);

// After parsing: the text options read into the problem and the search's options (InputError
// for a bad one), --output and this rank's checkpoint file (FILE, or FILE.r<rank> of `ranks`)
// checked writable, and `control` installed: its cancel always, its interruption with
// --checkpoint only (only then has a signal somewhere to save the run).
void prepare_grid_run(GridArgs& args, int rank, int ranks, const RunControl& control);

// The report's checkpoint fields (what it restarted from, what interrupted it and where it was
// saved), and --output written; returns the report as JSON (`hpcplan grid --json`'s object).
// `extra`'s keys are added to the object (before --output is written).
nlohmann::json finish_grid_run(GridReport& report, const GridArgs& args, const RunControl& control,
                               const nlohmann::json& extra = nlohmann::json::object());

}  // namespace hpcplan::cli
