#pragma once
// hpcplan planners' --world (one setting's planners), shared by the executable and the Python
// module's hpcplan.planners(world), so that both refuse an unknown setting in the same words.
#include <string>

#include <CLI/CLI.hpp>

namespace hpcplan::cli {

inline CLI::Option* add_planners_world_option(CLI::App* command, std::string& world) {
  return command->add_option("--world", world, "Only the planners of this setting")
      ->check(CLI::IsMember({"grid", "map3d", "sphere2d", "ompl", "sim"}));
}

}  // namespace hpcplan::cli
