#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan {

// The `hpcplan grid --json` contract: one object, keys documented in README.md.
nlohmann::json to_json(const GridReport& report, bool include_path);

// A readable multi-line summary for terminals.
std::string to_summary(const GridReport& report);

}  // namespace hpcplan
