#include "hpcplan/cli/grid_options.hpp"

#include <cmath>
#include <cstdlib>

#include "hpcplan/env/benchmark_spaces.hpp"

#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/io/grid_report_json.hpp"

namespace hpcplan::cli {

void add_grid_options(CLI::App* cmd, GridArgs& a) {
  auto& p = a.problem;
  a.dims_option =
      add_number(cmd, "--dims", p.dims, "Dimensions, 1..16 (required without --map)", 1, 16);
  cmd->add_option("--map", a.map,
                  "Plan on this occupancy file instead of GOG: a MovingAI .map (8-connected, no "
                  "corner cutting), a .3dmap voxel map (26-connected) or a NumPy .npy array "
                  "(bool/uint8, nonzero = blocked, 1..16 dimensions); --start/--goal in its "
                  "coordinates, x first (x = a .map's column, an array's last axis)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--world", a.world,
                  "Plan on a mechanism's configuration space instead of GOG: chain (OMPL's "
                  "kinematic chain, --dims links in the horn) | hypercube (OMPL's narrow passage "
                  "along the cube's edges); --start/--goal are then states in its coordinates "
                  "(radians, [0,1]), default the benchmark's query");
  add_number(cmd, "--cells", a.cells,
             "--world: lattice vertices per axis (0 = the space's default: for the chain 4 x links "
             "up to 6 links, 16 up to 8, 12 beyond; 11 for the hypercube)",
             0, 65535)
      ->capture_default_str();
  cmd->add_option("--moves", a.moves,
                  "--world: lattice moves, pairs (one or two axes, seed 002's rule) | axes (one)")
      ->capture_default_str();
  add_number(cmd, "--resolution", a.resolution,
             "--world: motion-check step as a fraction of the space's extent (0 = the "
             "benchmark's: 0.01 chain, 0.001 hypercube)",
             0, 1)
      ->capture_default_str();
  cmd->add_option("--checks", a.checks,
                  "--world: how the lattice tests states, batch (an expansion's successors, then "
                  "their edges' samples, at once) | single (one at a time; the same answers)")
      ->capture_default_str();
  cmd->add_option("--algo", a.algo,
                  "Planner (hpcplan planners --world grid): " + planner_names("grid"))
      ->capture_default_str();
  a.weight_option = add_param(cmd, "weight", a.weight)->capture_default_str();
  cmd->add_option("--heuristic", a.heuristic, "lattice (exact free-space cost) | euclidean")
      ->capture_default_str();
  a.gog_options.push_back(add_number(cmd, "--seed", p.gog.seed, "GOG seed")->capture_default_str());
  a.gog_options.push_back(
      add_number(cmd, "--extent", p.extent, "Lattice states per axis, 2..65535", 2, 65535)
          ->capture_default_str());
  cmd->add_option("--start", a.start, "Start state c1,c2,... (default: corner 0, adjusted)");
  cmd->add_option("--goal", a.goal, "Goal state (default: corner extent-1, adjusted)");
  add_param(cmd, "max_states", a.options.max_states)->capture_default_str();
  add_param(cmd, "time_limit", a.options.time_limit_s)->capture_default_str();
  add_param(cmd, "no_jump_points", a.no_jump_points);
  add_param(cmd, "engine", a.engine)->capture_default_str();
  add_param(cmd, "threads", a.options.threads)->capture_default_str();
  add_param(cmd, "memory_budget", a.options.memory_budget)->capture_default_str();
  add_param(cmd, "slab_layers", a.options.slab_layers)->capture_default_str();
  add_param(cmd, "contiguous_slabs", a.options.contiguous_slabs);
  a.connectivity_option =
      cmd->add_option("--connectivity", a.connectivity,
                      "seed (1 or 2 axes) | full (d <= 4); with --map: the format's own (seed "
                      "for .map and .npy, full for .3dmap)")
          ->capture_default_str();
  a.gog_options.push_back(add_number(cmd, "--threshold", p.gog.threshold,
                                     "GOG threshold c_v (0 = from --density)", 0, 49)
                              ->capture_default_str());
  a.gog_options.push_back(add_number(cmd, "--density", p.gog.density,
                                     "Blocked fraction aimed at by the automatic threshold", 0, 1)
                              ->capture_default_str());
  a.gog_options.push_back(
      add_number(cmd, "--gog-shift-p", p.gog.shift_p, "GOG b_p", 0, 63)->capture_default_str());
  a.gog_options.push_back(
      add_number(cmd, "--gog-shift-v", p.gog.shift_v, "GOG b_v", 0, 61)->capture_default_str());
  const char* ckpt = "Checkpoints (dense engine: --algo bfs or dijkstra)";
  cmd->add_option("--checkpoint", a.options.checkpoint,
                  "Write the search's state to FILE (FILE.r<rank> per rank under mpirun) at a "
                  "level or bucket boundary: every --checkpoint-every seconds, and on SIGUSR1, "
                  "SIGTERM or Ctrl-C, which then end the run (status interrupted, exit 0)")
      ->group(ckpt);
  add_number(cmd, "--checkpoint-every", a.options.checkpoint_every_s,
             "Seconds between checkpoints (0: only when interrupted)", 0, 1e9)
      ->capture_default_str()
      ->group(ckpt);
  cmd->add_option("--restart", a.options.restart,
                  "Continue from the checkpoint FILE of the same problem, ranks and threads")
      ->group(ckpt);
  cmd->add_flag("--path", a.options.keep_path, "Include the path");
  cmd->add_option("--output", a.output, "Also write the JSON result to this file (atomically)");
}

void add_field_option(CLI::App* cmd, GridArgs& a) {
  cmd->add_option("--field-out", a.field_out,
                  "Write the distance field of --start to FILE, a NumPy .npy of the map's shape "
                  "in NumPy order ((H, W) for a 2D map): int32 hop counts with --algo bfs, "
                  "float32 path costs with --algo dijkstra, -1 for blocked and unreachable "
                  "cells. The dense engine settles every reachable cell (--goal optional, still "
                  "reported); occupancy maps and GOG fields; serial or under mpirun (rank 0 "
                  "writes). Without --threads: one thread per 32768 states of the average "
                  "level (a 2D map: one)");
}

void check_field_request(const GridArgs& a) {
  if (a.field_out.empty()) return;
  validate_distance_field(a.problem, a.options);
  require_writable_destination(a.field_out, "--field-out");
}

nlohmann::json field_json(const DistanceField& f, const std::string& path, bool written,
                          bool goal_given) {
  nlohmann::json j;
  j["file"] = path;
  j["written"] = written;
  j["values"] = f.hops ? "hops" : "cost";
  j["dtype"] = f.hops ? "int32" : "float32";
  j["shape"] = f.numpy_shape();
  j["cells"] = f.cells();
  j["reached"] = f.reached;
  j["complete"] = f.complete;
  j["goal_given"] = goal_given;
  return j;
}

LoadedMap load_map(const std::string& path, const std::optional<std::vector<int>>& start,
                   Connectivity fallback) {
  const env::MapFormat format = env::map_format_of(path);
  auto grid = std::make_shared<OccupancyGrid>(env::load_occupancy(path));
  // A start in a .map's water plans over the water: its own class of cells.
  if (format == env::MapFormat::movingai && start && grid->inside(*start) &&
      !grid->is_free(*start)) {
    auto water = std::make_shared<OccupancyGrid>(env::load_occupancy(path, env::Terrain::water));
    if (water->is_free(*start)) grid = std::move(water);
  }
  LoadedMap m;
  m.grid = std::move(grid);
  const std::string_view own = env::published_connectivity(format);
  m.connectivity = own.empty() ? fallback : parse_connectivity(own);
  return m;
}

namespace {

// "0.1,-2,3e-1" -> {0.1, -2, 0.3}; InputError naming `what` on anything malformed.
std::vector<double> parse_reals(const std::string& text, const char* what) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw InputError(std::string(what) + " must be numbers separated by commas, got '" + text +
                       "'");
    out.push_back(v);
    at = comma + 1;
  }
  return out;
}

// --world: the space, its lattice and its query; GOG's and the maps' own options refused.
void prepare_cspace_problem(GridArgs& a, bool dims_given) {
  if (!a.map.empty()) throw InputError("--world and --map are two worlds: give one");
  const std::string what = a.space ? std::string("your space") : a.world;
  for (const CLI::Option* o : a.gog_options)
    if (o != nullptr && o->count() > 0)
      throw InputError(o->get_name() + " describes the GOG field; --world plans on " + what +
                       "'s configuration space");
  if (a.connectivity_option != nullptr && a.connectivity_option->count() > 0)
    throw InputError("--connectivity is the GOG lattice's; a --world lattice takes --moves");
  BenchmarkSpace b;
  if (a.space) {
    if (!a.world.empty()) throw InputError("world= and valid= are two spaces: give one");
    if (dims_given && a.problem.dims != a.space->dims())
      throw InputError("dims=" + std::to_string(a.problem.dims) + " but the space has " +
                       std::to_string(a.space->dims()) + " axes");
    if (a.cells <= 0 || a.start.empty() || a.goal.empty())
      throw InputError("a space of your own needs cells=, start= and goal=");
    b.space = a.space;
  } else {
    if (!dims_given)
      throw InputError(
          "--dims is required with --world (the chain's links, the hypercube's dimensions)");
    b = make_benchmark_space(a.world, a.problem.dims, a.resolution);
  }
  GridProblem p;
  p.dims = b.space->dims();
  p.extent = a.cells > 0 ? a.cells : b.cells;
  CSpaceQuery q;
  q.space = b.space;
  q.moves = parse_cspace_moves(a.moves);
  if (a.checks != "batch" && a.checks != "single")
    throw InputError("unknown --checks '" + a.checks + "' (expected batch or single)");
  q.batch_checks = a.checks == "batch";
  q.start = a.start.empty() ? b.start : parse_reals(a.start, "--start");
  q.goal = a.goal.empty() ? b.goal : parse_reals(a.goal, "--goal");
  p.cspace = std::move(q);
  a.problem = std::move(p);
}

}  // namespace

void prepare_grid_run(GridArgs& a, int rank, int ranks, const RunControl& control) {
  a.options.algorithm = parse_grid_algorithm(a.algo);
  a.options.heuristic = parse_heuristic(a.heuristic);
  a.problem.connectivity = parse_connectivity(a.connectivity);
  a.options.engine = parse_engine(a.engine);
  if (a.weight_option != nullptr && a.weight_option->count() > 0) a.options.weight = a.weight;
  a.options.jump_points = !a.no_jump_points;
  const bool dims_given = a.dims_option != nullptr && a.dims_option->count() > 0;
  if (!a.world.empty() || a.space) {
    prepare_cspace_problem(a, dims_given);
  } else {
    if (a.cells != 0 || a.resolution != 0.0 || a.checks != "batch")
      throw InputError(
          "--cells, --resolution and --checks describe a --world's lattice; give --world");
    if (!a.start.empty()) a.problem.start = parse_coordinates(a.start, "--start");
    if (!a.goal.empty()) a.problem.goal = parse_coordinates(a.goal, "--goal");
  }
  if (a.world.empty() && !a.space && !a.map.empty()) {
    for (const CLI::Option* o : a.gog_options)
      if (o != nullptr && o->count() > 0)
        throw InputError(o->get_name() +
                         " describes the GOG field; --map plans on the map's own "
                         "obstacles");
    const bool chosen = a.connectivity_option != nullptr && a.connectivity_option->count() > 0;
    LoadedMap m = load_map(a.map, a.problem.start, a.problem.connectivity);
    if (dims_given && a.problem.dims != m.grid->dims())
      throw InputError("--dims " + std::to_string(a.problem.dims) + " but '" + a.map + "' has " +
                       std::to_string(m.grid->dims()) + " dimensions");
    GridProblem p = occupancy_problem(m.grid, chosen ? a.problem.connectivity : m.connectivity);
    p.start = a.problem.start;
    p.goal = a.problem.goal;
    a.problem = std::move(p);
  } else if (a.world.empty() && !a.space && a.dims_option != nullptr && !dims_given) {
    throw InputError("--dims is required (or --map FILE to plan on a map)");
  }
  if (!a.output.empty()) require_writable_destination(a.output, "--output");
  a.options.cancel = control.cancel;
  if (!a.options.checkpoint.empty()) {
    require_writable_destination(dense::rank_file(a.options.checkpoint, rank, ranks),
                                 "--checkpoint");
    a.options.interrupted = [control] { return control.interrupted(); };
  }
}

nlohmann::json finish_grid_run(GridReport& report, const GridArgs& a, const RunControl& control,
                               const nlohmann::json& extra) {
  report.restarted_from = a.options.restart;
  if (report.result.status == Status::interrupted) {
    report.interrupted_by = control.stopped_by();
    report.checkpoint = a.options.checkpoint;
  }
  nlohmann::json json = to_json(report, a.options.keep_path);
  for (const auto& [key, value] : extra.items()) json[key] = value;
  if (!a.output.empty()) write_file_atomically(a.output, json.dump() + "\n");
  return json;
}

}  // namespace hpcplan::cli
