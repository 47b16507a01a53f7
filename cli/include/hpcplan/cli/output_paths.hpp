#pragma once
// Checks on the file options of the long-running subcommands (hpcplan sph, hpcplan sim), made
// before the run starts.
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <CLI/CLI.hpp>

#include "hpcplan/core/error.hpp"

namespace hpcplan::cli {

// An empty path (an unset shell variable in a job script) is refused, not taken as "none".
inline void refuse_empty_paths(CLI::App* cmd, std::initializer_list<const char*> options) {
  for (const char* name : options)
    cmd->get_option(name)->check([](const std::string& v) {
      return v.empty() ? std::string("an empty path") : std::string();
    });
}

// One file, one content: two options naming the same file (after resolving links and dots)
// would overwrite each other. Options not given (empty) are skipped.
inline void require_distinct_outputs(
    std::initializer_list<std::pair<const std::string*, const char*>> outputs) {
  for (auto i = outputs.begin(); i != outputs.end(); ++i)
    for (auto j = std::next(i); j != outputs.end(); ++j)
      if (!i->first->empty() && !j->first->empty() &&
          std::filesystem::weakly_canonical(*i->first) ==
              std::filesystem::weakly_canonical(*j->first))
        throw InputError(std::string(i->second) + " '" + *i->first +
                         "' is also another output's file (" + j->second + ")");
}

}  // namespace hpcplan::cli
