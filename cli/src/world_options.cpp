#include "hpcplan/cli/world_options.hpp"

#include "hpcplan/cli/number_options.hpp"

namespace hpcplan::cli {

double default_resolution(const std::string& world) {
  return world == "sphere2d" ? 0.25 : 0.1;
}

void add_world_planner_options(CLI::App* cmd, plan::WorldPlanOptions& o, const std::string& world) {
  o.resolution = default_resolution(world);
  cmd->add_option("--algo", o.algo,
                  "Planner (hpcplan planners --world " + world + "): " + planner_names(world))
      ->capture_default_str();
  add_param(cmd, "resolution", o.resolution)->capture_default_str();
  add_param(cmd, "spacing", o.spacing)->capture_default_str();
  add_param(cmd, "weight", o.weight)->capture_default_str();
  add_param(cmd, "seed", o.seed)->capture_default_str();
  add_param(cmd, "time", o.time_s)->capture_default_str();
  add_param(cmd, "step", o.step)->capture_default_str();
  add_param(cmd, "samples", o.samples_per_expansion)->capture_default_str();
  add_param(cmd, "max_states", o.max_states);
  add_param(cmd, "shortcut", o.shortcut);
  add_param(cmd, "stop_at_first", o.stop_at_first);
}

}  // namespace hpcplan::cli
