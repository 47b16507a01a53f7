// hpcplan map3d / hpcplan sphere2d: one plan in a continuous world (a seed 004 box map, or a
// seed 003 sphere world) with any of the world planners, as a summary table or JSON.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "hpcplan/cli/point_option.hpp"
#include "hpcplan/cli/world_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/io/path_csv.hpp"
#include "hpcplan/io/world_plan_json.hpp"
#include "hpcplan/plan/world_planner.hpp"

namespace hpcplan::cli {

namespace {

struct WorldArgs {
  std::string map, start, goal, path_out, output;
  plan::WorldPlanOptions options;
  bool json = false;
};

// The query point: the option when given, else the map's own line.
template <int D>
env::Vec<D> query_point(const std::string& option_text, const std::optional<env::Vec<D>>& from_map,
                        const char* option, const char* what) {
  if (!option_text.empty()) return parse_point<D>(option_text, option);
  if (from_map) return *from_map;
  throw InputError(std::string("no ") + option + " given and the map has no " + what + " line");
}

template <class Map>
int run(const WorldArgs& a, const Map& map) {
  constexpr int D = std::remove_cvref_t<decltype(map.world)>::kDim;
  const env::Vec<D> start = query_point<D>(a.start, map.start, "--start", "start");
  const env::Vec<D> goal = query_point<D>(a.goal, map.goal, "--goal", "goal");

  const plan::WorldPlan<D> p = plan::plan_in_world(map.world, start, goal, a.options);
  const std::string json = to_json(p).dump() + "\n";
  if (!a.output.empty()) write_file_atomically(a.output, json);
  if (!a.path_out.empty() && p.status == Status::solved)
    write_file_atomically(a.path_out, path_csv<D>(p.path));
  std::fputs(a.json ? json.c_str() : to_summary(p, a.map).c_str(), stdout);
  // No path is an answer (exit 0, status in the output); a hint on stderr says what to try.
  if (p.status != Status::solved) {
    std::fflush(stdout);
    std::fprintf(stderr, "hpcplan: %s found no path (%s)%s\n", p.algo.c_str(),
                 std::string(to_string(p.status)).c_str(),
                 p.status == Status::timeout ? "; raise --time"
                 : p.algo == "visgraph"      ? "; try a finer --spacing"
                                             : "; try a finer --resolution");
  }
  return kExitOk;
}

void add_common(CLI::App* cmd, const std::shared_ptr<WorldArgs>& args, const std::string& world,
                const char* point) {
  cmd->add_option("--map", args->map, "World file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--start", args->start, std::string("Start ") + point + " (default: the map's)");
  cmd->add_option("--goal", args->goal, std::string("Goal ") + point + " (default: the map's)");
  add_world_planner_options(cmd, args->options, world);
  cmd->add_flag("--json", args->json, "Print one JSON object instead of a summary");
  cmd->add_option("--path-out", args->path_out, "Write the path as CSV (atomically)");
  cmd->add_option("--output", args->output, "Also write the JSON result to this file (atomically)");
}

template <class Load>
Action register_world_command(CLI::App& app, const std::string& name, const std::string& about,
                              const char* point, Load load) {
  auto args = std::make_shared<WorldArgs>();
  add_common(app.add_subcommand(name, about), args, name, point);
  return [args, name, load](const Context& context) {
    if (context.comm && context.comm->size() > 1)
      throw InputError(name + " runs in one process; start it without mpirun");
    if (!args->output.empty()) require_writable_destination(args->output, "--output");
    if (!args->path_out.empty()) require_writable_destination(args->path_out, "--path-out");
    return run(*args, load(args->map));
  };
}

}  // namespace

Action register_map3d_command(CLI::App& app) {
  return register_world_command(app, "map3d", "Plan in a 3D box map (seeds 001/004)", "x,y,z",
                                env::load_box_map);
}

Action register_sphere2d_command(CLI::App& app) {
  return register_world_command(app, "sphere2d", "Plan in a 2D sphere world (seed 003)", "x,y",
                                env::load_sphere_map);
}

}  // namespace hpcplan::cli
