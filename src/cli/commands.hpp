#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace hpcplan::cli {

// Each subcommand registers its options on `app` and returns the action that runs it; the
// action returns the process exit code and may throw InputError / RunError.
using Action = std::function<int()>;
Action register_grid_command(CLI::App& app);

}  // namespace hpcplan::cli
