// Every planner on every world file, repeated: one CSV row per run (time, length, work), and
// optionally each configuration's first solved path as CSV for the figures. Configurations are
// "algo[@resolution][+shortcut]", e.g. astar@0.1, thetastar@0.25+shortcut, rrtstar+shortcut;
// for visgraph the number is the bend spacing (visgraph@0.25+shortcut).
//   hpcplan_world_sweep --kind map3d --maps bench/maps/maze.txt ... --configs astar@0.1,rrt
//       --runs 5 --time 1 --out results/map3d/sweep.csv --paths results/map3d/paths
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/progress.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/io/path_csv.hpp"
#include "hpcplan/io/world_plan_json.hpp"
#include "hpcplan/plan/planner_registry.hpp"
#include "hpcplan/plan/world_planner.hpp"

namespace {

using namespace hpcplan;

struct Config {
  std::string label;
  plan::WorldPlanOptions options;
};

Config parse_config(const std::string& text, const plan::WorldPlanOptions& base) {
  Config c{text, base};
  std::string s = text;
  if (const auto plus = s.find("+shortcut"); plus != std::string::npos) {
    c.options.shortcut = true;
    s.erase(plus);
  }
  if (const auto at = s.find('@'); at != std::string::npos) {
    // The grid searches' cell size, or the visibility graph's bend spacing.
    (s.starts_with("visgraph") ? c.options.spacing : c.options.resolution) =
        std::stod(s.substr(at + 1));
    s.erase(at);
  }
  c.options.algo = s;
  return c;
}

template <class Map>
void sweep(const std::string& name, const Map& map, const std::vector<Config>& configs, int runs,
           std::string& csv, const std::string& paths_dir, Progress& progress) {
  constexpr int D = std::remove_cvref_t<decltype(map.world)>::kDim;
  for (const Config& c : configs) {
    bool path_written = false;
    for (int run = 0; run < runs; ++run) {
      plan::WorldPlanOptions o = c.options;
      o.seed = static_cast<std::uint64_t>(run + 1);
      const plan::WorldPlan<D> p = plan::plan_in_world(map.world, *map.start, *map.goal, o);
      csv += to_csv_row(p, name, c.label, run + 1);
      if (!paths_dir.empty() && !path_written && p.status == Status::solved) {
        write_file_atomically(paths_dir + "/" + name + "__" + c.label + ".csv",
                              path_csv<D>(p.path));
        path_written = true;
      }
      progress.step(name + " " + c.label);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hpcplan world sweep: planners x world files x runs"};
  std::string kind = "map3d", out, paths_dir, config_text;
  std::vector<std::string> maps;
  int runs = 3;
  plan::WorldPlanOptions base;
  app.add_option("--kind", kind, "map3d or sphere2d")->check(CLI::IsMember({"map3d", "sphere2d"}));
  app.add_option("--maps", maps, "World files (with start and goal lines)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--configs", config_text, "Comma-separated algo[@resolution][+shortcut]")
      ->required();
  app.add_option("--runs", runs, "Runs per configuration (seeds 1..runs)")
      ->check(CLI::PositiveNumber);
  app.add_option("--time", base.time_s, "Planner time limit (anytime planners use all of it)");
  app.add_option("--samples", base.samples_per_expansion, "Hybrid samples per expansion");
  app.add_option("--out", out, "CSV file (written atomically)")->required();
  app.add_option("--paths", paths_dir, "Folder for each configuration's first path");
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<Config> configs;
    std::stringstream in(config_text);
    for (std::string item; std::getline(in, item, ',');) {
      configs.push_back(parse_config(item, base));
      // Fail before the first run, not hours in: every name must be a registered planner.
      plan::PlannerRegistry::get().require(kind, configs.back().options.algo);
    }
    if (!paths_dir.empty()) std::filesystem::create_directories(paths_dir);
    std::string csv = world_plan_csv_header();
    Progress progress("sweep", maps.size() * configs.size() * static_cast<std::size_t>(runs));
    for (const std::string& file : maps) {
      const std::string name = std::filesystem::path(file).stem().string();
      if (kind == "map3d")
        sweep(name, env::load_box_map(file), configs, runs, csv, paths_dir, progress);
      else
        sweep(name, env::load_sphere_map(file), configs, runs, csv, paths_dir, progress);
    }
    write_file_atomically(out, csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hpcplan_world_sweep: error: %s\n", e.what());
    return dynamic_cast<const InputError*>(&e) ? 2 : 1;
  }
  return 0;
}
