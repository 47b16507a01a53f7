// `hpcplan planners`: the planner registry, as a listing or JSON.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "hpcplan/cli/planners_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/io/planners_json.hpp"

namespace hpcplan::cli {

Action register_planners_command(CLI::App& app) {
  struct Args {
    bool json = false;
    std::string world;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("planners", "List every planner, where it runs, its options");
  cmd->add_flag("--json", args->json, "Print one JSON object");
  add_planners_world_option(cmd, args->world);
  return [args](const Context& context) {
    if (!context.is_root()) return kExitOk;
    const auto& registry = plan::PlannerRegistry::get();
    if (args->json)
      std::puts(to_json(registry, args->world).dump().c_str());
    else
      std::fputs(to_summary(registry, args->world).c_str(), stdout);
    return kExitOk;
  };
}

}  // namespace hpcplan::cli
